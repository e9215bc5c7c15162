#include "groundstation/client/agent_client.hpp"

#include <memory>
#include <string>

#include "kapfix/v1/envelope_codec.hpp"
#include "link/envelope.hpp"
#include "link/topic_names.hpp"
#include "link/topic_table.hpp"

namespace kapfix::station {
namespace {

QByteArray Bytes(std::string_view text) {
  return {text.data(), static_cast<qsizetype>(text.size())};
}

}  // namespace

AgentClient::AgentClient(QObject* parent) : QObject(parent) {}

AgentClient::~AgentClient() = default;

bool AgentClient::deliverMessage(std::string_view topic, std::string_view payload,
                                 std::int64_t receive_time_us) {
  std::unique_ptr<google::protobuf::Message> message = kapfix::link::NewMessageForTopic(topic);
  if (message == nullptr || !kapfix::link::DecodeEnvelope(topic, payload, message.get(),
                                                          kapfix::v1::kMaxMessageBytes, nullptr)) {
    return false;
  }
  if (topic == kapfix::link::kHeartbeatTopic) return true;
  emit messageReceived(QString::fromUtf8(topic.data(), static_cast<qsizetype>(topic.size())),
                       Bytes(payload), receive_time_us);
  // The casts are safe: DecodeEnvelope checked that `message` is the type of `topic`.
  if (topic == kapfix::link::kTelemetryTopic) {
    emit telemetryReceived(static_cast<const kapfix::v1::Telemetry&>(*message));
  } else if (topic == kapfix::link::kVideoTopic) {
    emit videoFrameReceived(static_cast<const kapfix::v1::VideoFrame&>(*message));
  } else if (topic == kapfix::link::kSlicesTopic) {
    emit sliceReportReceived(static_cast<const kapfix::v1::SliceReport&>(*message));
  } else if (topic == kapfix::link::kPssTopic) {
    emit pssReportReceived(static_cast<const kapfix::v1::PssReport&>(*message));
  } else if (topic == kapfix::link::kCalibrationTopic) {
    emit calibrationReceived(static_cast<const kapfix::v1::CalibrationReport&>(*message));
  } else if (topic == kapfix::link::kStateTopic) {
    emit stateReceived(static_cast<const kapfix::v1::AgentState&>(*message));
  } else if (topic == kapfix::link::kPhotoTopic) {
    emit photoChunkReceived(static_cast<const kapfix::v1::Photo&>(*message));
  } else if (topic == kapfix::link::kLogTopic) {
    emit logReceived(static_cast<const kapfix::v1::Log&>(*message));
  } else if (topic == kapfix::link::kCommandTopic) {
    emit commandSent(static_cast<const kapfix::v1::Command&>(*message));
  } else if (topic == kapfix::link::kReplyTopic) {
    const auto& reply = static_cast<const kapfix::v1::Reply&>(*message);
    emit replyReceived(reply);
    if (reply.has_state()) emit stateReceived(reply.state());
  }
  return true;
}

void AgentClient::announceCommand(const kapfix::v1::Command& command) {
  // The recorded copy carries a header of its own so that a replay decodes it like any
  // other message; the link stamps the real one.
  kapfix::v1::Command recorded = command;
  kapfix::v1::Stamp(recorded.mutable_header(), recorded.header().agent_id(), 0);
  const kapfix::link::Envelope envelope = kapfix::link::Encode(recorded);
  emit messageReceived(QString::fromStdString(envelope.topic), Bytes(envelope.payload),
                       kapfix::v1::NowMicros());
  emit commandSent(recorded);
}

void AgentClient::finishCommand(const CommandOutcome& outcome, const ReplyCallback& done) {
  if (outcome.answered) {
    const kapfix::link::Envelope envelope = kapfix::link::Encode(outcome.reply);
    emit messageReceived(QString::fromStdString(envelope.topic), Bytes(envelope.payload),
                         kapfix::v1::NowMicros());
    emit replyReceived(outcome.reply);
    if (outcome.reply.has_state()) emit stateReceived(outcome.reply.state());
  }
  if (done) done(outcome);
}

}  // namespace kapfix::station
