#pragma once

// A scriptable stand-in for an agent, for panel tests and offline checks: it records every
// command, answers each as told (accept, refuse with a reason, or stay silent), and emits
// whatever messages a test hands it — encoded and decoded again through deliverMessage(),
// so the panels see exactly what the live link would give them.

#include <google/protobuf/message.h>

#include <map>
#include <string>
#include <vector>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class FakeAgentClient final : public AgentClient {
  Q_OBJECT

 public:
  explicit FakeAgentClient(QObject* parent = nullptr);

  void sendCommand(kapfix::v1::Command command, ReplyCallback done = {}) override;
  LinkState linkState() const override { return state_; }

  // Every command sent, oldest first.
  const std::vector<kapfix::v1::Command>& commands() const { return commands_; }
  // The last command of this kind; nullptr when none was sent.
  const kapfix::v1::Command* lastCommand(kapfix::v1::Command::CommandCase kind) const;

  // Later commands of `kind` are refused with this reason (ERROR_CODE_OUT_OF_RANGE).
  void refuse(kapfix::v1::Command::CommandCase kind, const std::string& reason);
  // Later commands of `kind` are accepted again.
  void accept(kapfix::v1::Command::CommandCase kind) { refusals_.erase(kind); }
  // Later commands get no reply at all (the link dropped them).
  void setSilent(bool silent) { silent_ = silent; }
  // The state returned to request_state.
  void setAgentState(const kapfix::v1::AgentState& state) { agent_state_ = state; }

  // Emits `message` as if it had arrived on its topic (stamped with a header first).
  void publish(const google::protobuf::Message& message);
  void setLink(const LinkState& state);
  // A new agent process from now on: its stream sequences start again at 1, and its
  // messages carry `boot_id` (0: none, as an older agent).
  void restartAgent(std::uint64_t boot_id = 0) {
    sequence_ = 0;
    boot_id_ = boot_id;
  }
  // The boot id every message carries from now on (0: none).
  void setBootId(std::uint64_t boot_id) { boot_id_ = boot_id; }

 private:
  std::vector<kapfix::v1::Command> commands_;
  std::map<kapfix::v1::Command::CommandCase, std::string> refusals_;
  bool silent_ = false;
  kapfix::v1::AgentState agent_state_;
  LinkState state_;
  std::uint64_t sequence_ = 0;
  std::uint64_t boot_id_ = 0;
};

}  // namespace kapfix::station
