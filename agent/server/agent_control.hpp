#pragma once

// The seam between the link and the rest of the agent: CommandServer talks to the agent only
// through this interface, so the link can be built and tested without the capture, match and
// control pipeline (a fake stands in for it in tests/link).

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/state.pb.h"

namespace kapfix::agent {

class AgentControl {
 public:
  virtual ~AgentControl() = default;

  // Carries out one command. It arrives already decoded, version-checked, sequence-checked
  // and range-checked (CommandValidator), so an implementation only refuses what depends on
  // the agent's situation (wrong mode, hardware, storage), with Reply.error and Reply.reason.
  // Runs on the command server's thread: return promptly, never wait for a process to end
  // (a mode switch starts it; its results travel on the streams). The server fills the
  // reply's header and command_sequence; for request_state it fills Reply.state from State()
  // when the reply leaves it empty.
  virtual kapfix::v1::Reply Execute(const kapfix::v1::Command& command) = 0;

  // The current settings and latest results. The validator reads the frame size and slice
  // count from it to range-check patch sizes and slice indices. Called from the command
  // server's thread; must be safe against the agent's own threads changing the state.
  virtual kapfix::v1::AgentState State() const = 0;
};

}  // namespace kapfix::agent
