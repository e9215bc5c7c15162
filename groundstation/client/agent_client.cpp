#include "groundstation/client/agent_client.hpp"

#include <memory>
#include <string>

#include "kapfix/v1/envelope_codec.hpp"

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
  std::unique_ptr<google::protobuf::Message> message = kapfix::v1::NewMessageForTopic(topic);
  if (message == nullptr || !kapfix::v1::DecodeEnvelope(topic, payload, message.get(),
                                                        kapfix::v1::kMaxMessageBytes, nullptr)) {
    return false;
  }
  if (topic == "heartbeat") return true;
  emit messageReceived(QString::fromUtf8(topic.data(), static_cast<qsizetype>(topic.size())),
                       Bytes(payload), receive_time_us);
  // The casts are safe: DecodeEnvelope checked that `message` is the type of `topic`.
  if (topic == "telemetry") {
    emit telemetryReceived(static_cast<const kapfix::v1::Telemetry&>(*message));
  } else if (topic == "video") {
    emit videoFrameReceived(static_cast<const kapfix::v1::VideoFrame&>(*message));
  } else if (topic == "slices") {
    emit sliceReportReceived(static_cast<const kapfix::v1::SliceReport&>(*message));
  } else if (topic == "pss") {
    emit pssReportReceived(static_cast<const kapfix::v1::PssReport&>(*message));
  } else if (topic == "calibration") {
    emit calibrationReceived(static_cast<const kapfix::v1::CalibrationReport&>(*message));
  } else if (topic == "state") {
    emit stateReceived(static_cast<const kapfix::v1::AgentState&>(*message));
  } else if (topic == "photo") {
    emit photoChunkReceived(static_cast<const kapfix::v1::Photo&>(*message));
  } else if (topic == "log") {
    emit logReceived(static_cast<const kapfix::v1::Log&>(*message));
  } else if (topic == "command") {
    emit commandSent(static_cast<const kapfix::v1::Command&>(*message));
  } else if (topic == "reply") {
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
  const kapfix::v1::Envelope envelope = kapfix::v1::Encode(recorded);
  emit messageReceived(QString::fromStdString(envelope.topic), Bytes(envelope.payload),
                       kapfix::v1::NowMicros());
  emit commandSent(recorded);
}

void AgentClient::finishCommand(const CommandOutcome& outcome, const ReplyCallback& done) {
  if (outcome.answered) {
    const kapfix::v1::Envelope envelope = kapfix::v1::Encode(outcome.reply);
    emit messageReceived(QString::fromStdString(envelope.topic), Bytes(envelope.payload),
                         kapfix::v1::NowMicros());
    emit replyReceived(outcome.reply);
    if (outcome.reply.has_state()) emit stateReceived(outcome.reply.state());
  }
  if (done) done(outcome);
}

}  // namespace kapfix::station
