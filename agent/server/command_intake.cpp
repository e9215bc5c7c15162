#include "agent/server/command_intake.hpp"

#include <exception>
#include <utility>

#include "link/envelope.hpp"
#include "link/topic_names.hpp"

namespace kapfix::agent {
namespace {

using kapfix::v1::Command;
using kapfix::v1::ErrorCode;
using kapfix::v1::Reply;

using kapfix::link::kCommandTopic;

}  // namespace

CommandIntake::CommandIntake(AgentControl& control, std::string agent_id, CommandLimits limits,
                             const std::optional<ReplayWindowOptions>& replay)
    : control_(control), agent_id_(std::move(agent_id)), validator_(limits) {
  if (replay) replay_ = std::make_unique<ReplayWindow>(*replay, kapfix::v1::NowMicros());
}

CommandIntake::Outcome CommandIntake::Answer(std::string_view sender,
                                             std::optional<std::string_view> topic,
                                             std::string_view payload, std::string_view station) {
  Outcome outcome;
  Command command;
  outcome.reply = Check(sender, topic, payload, station, command, outcome.station_heard);
  outcome.command_sequence = command.header().sequence();
  if (outcome.reply.error() != kapfix::v1::ERROR_CODE_UNSPECIFIED) return outcome;
  try {
    outcome.reply = control_.Execute(command);
    if (command.has_request_state() && outcome.reply.ok() && !outcome.reply.has_state()) {
      *outcome.reply.mutable_state() = control_.State();
    }
  } catch (const std::exception& error) {
    outcome.reply = Reply();
    outcome.reply.set_error(kapfix::v1::ERROR_CODE_INTERNAL);
    outcome.reply.set_reason(std::string("the agent failed to execute the command: ") +
                             error.what());
  }
  return outcome;
}

// Everything before Execute: decoding, addressing, replay, ranges. An error reply, or a reply
// with error UNSPECIFIED when the command may go on; `command` holds what could be read.
Reply CommandIntake::Check(std::string_view sender, std::optional<std::string_view> topic,
                           std::string_view payload, std::string_view station, Command& command,
                           bool& station_heard) {
  Reply reply;
  std::string error;
  ErrorCode code = kapfix::v1::ERROR_CODE_UNSPECIFIED;
  if (!kapfix::link::DecodeEnvelope(topic.value_or(kCommandTopic), payload, &command,
                                    kapfix::v1::kMaxCommandBytes, &error, &code)) {
    if (code == kapfix::v1::ERROR_CODE_WRONG_VERSION) {
      // The bytes parse; read them anyway, only so the reply can name the command's sequence
      // and the station can match it to its request.
      Command readable;
      if (readable.ParseFromArray(payload.data(), static_cast<int>(payload.size()))) {
        *command.mutable_header() = readable.header();
      }
    }
    reply.set_error(code);
    reply.set_reason(error);
    return reply;
  }
  const std::string& addressed = command.header().agent_id();
  if (!addressed.empty() && addressed != agent_id_) {
    reply.set_error(kapfix::v1::ERROR_CODE_UNAUTHORIZED);
    // Echoed only when short: cutting it could split a UTF-8 character, and a reply with
    // invalid UTF-8 in a string would not parse at the station.
    constexpr std::size_t kMaxEchoed = 64;
    reply.set_reason("command addressed to agent " +
                     (addressed.size() <= kMaxEchoed ? "'" + addressed + "'" : "(a long id)") +
                     ", this is agent '" + agent_id_ + "'");
    return reply;
  }
  if (!guard_.Accept(sender, command.header().sequence(), &error) ||
      (replay_ && !replay_->Accept(station, command.header().send_time_us(),
                                   command.header().sequence(), kapfix::v1::NowMicros(), &error))) {
    reply.set_error(kapfix::v1::ERROR_CODE_STALE_SEQUENCE);
    reply.set_reason(error);
    return reply;
  }
  station_heard = true;
  try {
    return validator_.Validate(
        // Only the commands whose ranges depend on it take a state snapshot (it takes the lock
        // the control thread reports its mode and results under): not request_state.
        command,
        CommandValidator::NeedsState(command) ? control_.State() : kapfix::v1::AgentState());
  } catch (const std::exception& failure) {
    reply.set_error(kapfix::v1::ERROR_CODE_INTERNAL);
    reply.set_reason(std::string("the agent could not report its state: ") + failure.what());
    return reply;
  }
}

}  // namespace kapfix::agent
