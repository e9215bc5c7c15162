#include "link/topic_table.hpp"

#include <google/protobuf/descriptor.h>

#include <array>

#include "kapfix/v1/calibration.pb.h"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/heartbeat.pb.h"
#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/photo.pb.h"
#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/state.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"
#include "link/topic_names.hpp"

namespace kapfix::link {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::Message;

struct TopicEntry {
  std::string_view topic;
  const Message* prototype;
};

constexpr std::size_t kTopicCount = 11;

const std::array<TopicEntry, kTopicCount>& Table() {
  static const std::array<TopicEntry, kTopicCount> table = {{
      {kTelemetryTopic, &kapfix::v1::Telemetry::default_instance()},
      {kVideoTopic, &kapfix::v1::VideoFrame::default_instance()},
      {kSlicesTopic, &kapfix::v1::SliceReport::default_instance()},
      {kPssTopic, &kapfix::v1::PssReport::default_instance()},
      {kCalibrationTopic, &kapfix::v1::CalibrationReport::default_instance()},
      {kPhotoTopic, &kapfix::v1::Photo::default_instance()},
      {kLogTopic, &kapfix::v1::Log::default_instance()},
      {kHeartbeatTopic, &kapfix::v1::Heartbeat::default_instance()},
      {kCommandTopic, &kapfix::v1::Command::default_instance()},
      {kReplyTopic, &kapfix::v1::Reply::default_instance()},
      {kStateTopic, &kapfix::v1::AgentState::default_instance()},
  }};
  return table;
}

}  // namespace

std::string TopicFor(const Message& message) {
  const Descriptor& type = *message.GetDescriptor();
  for (const TopicEntry& entry : Table()) {
    // By name, so that a DynamicMessage of the same type (another descriptor pool) matches.
    if (entry.prototype->GetDescriptor()->full_name() == type.full_name()) {
      return std::string(entry.topic);
    }
  }
  return {};
}

const std::vector<std::string>& Topics() {
  static const std::vector<std::string> topics = [] {
    std::vector<std::string> names;
    for (const TopicEntry& entry : Table()) names.emplace_back(entry.topic);
    return names;
  }();
  return topics;
}

std::unique_ptr<Message> NewMessageForTopic(std::string_view topic) {
  for (const TopicEntry& entry : Table()) {
    if (topic == entry.topic) return std::unique_ptr<Message>(entry.prototype->New());
  }
  return nullptr;
}

}  // namespace kapfix::link
