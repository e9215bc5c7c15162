#include "groundstation/client/fake_agent_client.hpp"

#include <QMetaObject>
#include <memory>
#include <utility>

#include "kapfix/v1/envelope_codec.hpp"
#include "link/envelope.hpp"

namespace kapfix::station {
namespace {

constexpr const char* kFakeAgentId = "fake-agent";

}  // namespace

FakeAgentClient::FakeAgentClient(QObject* parent) : AgentClient(parent) {
  state_.source = QStringLiteral("fake");
}

const kapfix::v1::Command* FakeAgentClient::lastCommand(
    kapfix::v1::Command::CommandCase kind) const {
  for (auto it = commands_.rbegin(); it != commands_.rend(); ++it) {
    if (it->command_case() == kind) return &*it;
  }
  return nullptr;
}

void FakeAgentClient::refuse(kapfix::v1::Command::CommandCase kind, const std::string& reason) {
  refusals_[kind] = reason;
}

void FakeAgentClient::sendCommand(kapfix::v1::Command command, ReplyCallback done) {
  announceCommand(command);
  commands_.push_back(command);
  if (silent_) {
    CommandOutcome outcome;
    outcome.reason = tr("no answer (fake agent silent)");
    QMetaObject::invokeMethod(
        this, [this, outcome, done = std::move(done)] { finishCommand(outcome, done); },
        Qt::QueuedConnection);
    return;
  }
  CommandOutcome outcome;
  outcome.answered = true;
  kapfix::v1::Reply& reply = outcome.reply;
  kapfix::v1::Stamp(reply.mutable_header(), kFakeAgentId, ++sequence_);
  reply.set_command_sequence(commands_.size());
  if (const auto refusal = refusals_.find(command.command_case()); refusal != refusals_.end()) {
    reply.set_ok(false);
    reply.set_error(kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
    reply.set_reason(refusal->second);
  } else {
    reply.set_ok(true);
    if (command.has_request_state()) *reply.mutable_state() = agent_state_;
  }
  outcome.ok = reply.ok();
  outcome.reason = QString::fromStdString(reply.reason());
  QMetaObject::invokeMethod(
      this, [this, outcome, done = std::move(done)] { finishCommand(outcome, done); },
      Qt::QueuedConnection);
}

void FakeAgentClient::publish(const google::protobuf::Message& message) {
  std::unique_ptr<google::protobuf::Message> stamped(message.New());
  stamped->CopyFrom(message);
  // Every link message has its Header at field 1 (header.proto's rule).
  const auto* field = stamped->GetDescriptor()->FindFieldByNumber(1);
  if (field != nullptr && field->message_type() == kapfix::v1::Header::descriptor()) {
    auto* header = static_cast<kapfix::v1::Header*>(
        stamped->GetReflection()->MutableMessage(stamped.get(), field));
    kapfix::v1::Stamp(header, kFakeAgentId, ++sequence_);
    header->set_boot_id(boot_id_);
  }
  const kapfix::link::Envelope envelope = kapfix::link::Encode(*stamped);
  deliverMessage(envelope.topic, envelope.payload, kapfix::v1::NowMicros());
}

void FakeAgentClient::setLink(const LinkState& state) {
  if (state == state_) return;
  state_ = state;
  emit linkChanged(state_);
}

}  // namespace kapfix::station
