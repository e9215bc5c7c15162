#pragma once

// One command request's payload in, the agent's Reply out (SPEC §5), without the socket: the
// bytes are decoded and their version checked, the command's address and sequence number
// checked, its values range-checked (CommandValidator), and only then is it handed to
// AgentControl. CommandServer feeds it what arrives on its ROUTER socket; the fuzzers of
// tests/fuzz feed it arbitrary bytes. Not thread-safe: one owner (the server thread).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "agent/server/agent_control.hpp"
#include "agent/server/command_validator.hpp"
#include "agent/server/replay_window.hpp"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"

namespace kapfix::agent {

class CommandIntake {
 public:
  // What one request came to.
  struct Outcome {
    // The answer: from AgentControl when every check passed, otherwise an error naming the
    // problem. Header and command_sequence are left to the caller.
    kapfix::v1::Reply reply;
    std::uint64_t command_sequence = 0;  // [count] the command's header.sequence; 0 = unreadable
    // The request got past the replay check: it shows the station is alive (link-loss
    // detection), whether or not its values were accepted.
    bool station_heard = false;
  };

  // `control` must outlive the intake. `agent_id`: commands addressed to another agent are
  // refused (an empty header.agent_id addresses any).
  // `replay`: refuse commands replayed on another connection or outside the clock window
  // (ReplayWindow); unset: per-connection sequence numbers only.
  CommandIntake(AgentControl& control, std::string agent_id, CommandLimits limits = {},
                const std::optional<ReplayWindowOptions>& replay = std::nullopt);

  // Answers one request. `sender` identifies the station reliably (ROUTER routing id or CURVE
  // key): sequence numbers are checked per sender. `topic` is the request's topic frame when
  // it had one ("command" is the only one accepted); without one the payload is a command.
  // `station` names the station across connections (its CURVE key or name; empty for a
  // plain station) for the replay window. Never throws for anything in the request; an
  // exception from AgentControl becomes an ERROR_CODE_INTERNAL reply.
  Outcome Answer(std::string_view sender, std::optional<std::string_view> topic,
                 std::string_view payload, std::string_view station = {});

 private:
  kapfix::v1::Reply Check(std::string_view sender, std::optional<std::string_view> topic,
                          std::string_view payload, std::string_view station,
                          kapfix::v1::Command& command, bool& station_heard);

  AgentControl& control_;
  const std::string agent_id_;
  const CommandValidator validator_;
  kapfix::v1::SequenceGuard guard_;
  std::unique_ptr<ReplayWindow> replay_;  // null: off
};

}  // namespace kapfix::agent
