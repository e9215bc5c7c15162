#pragma once

// Which kapfix.v1 message type travels under which topic (topic_names.hpp): the one table
// the agent's server, the client, the station, the session file and the fuzzers share.

#include <google/protobuf/message.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace kapfix::link {

// The topic a message type travels under; empty for a type that does not travel on its own
// (Header, Rect, settings…).
std::string TopicFor(const google::protobuf::Message& message);

// Every topic: telemetry, video, slices, pss, calibration, photo, log, heartbeat, command,
// reply, state.
const std::vector<std::string>& Topics();

// A new, empty message of the type a topic carries; nullptr for an unknown topic.
std::unique_ptr<google::protobuf::Message> NewMessageForTopic(std::string_view topic);

}  // namespace kapfix::link
