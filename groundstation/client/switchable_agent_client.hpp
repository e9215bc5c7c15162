#pragma once

// What the views watch: forwards one source at a time — the live agent, or a recording
// being replayed — so that a replay shows in exactly the same panels as the live link.
// Commands go to the current source (a replay refuses them with its reason).

#include <QMetaObject>
#include <QPointer>
#include <vector>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class SwitchableAgentClient final : public AgentClient {
  Q_OBJECT

 public:
  explicit SwitchableAgentClient(AgentClient& source, QObject* parent = nullptr);

  // Forwards `source` from now on (not owned; must outlive its use here) and announces
  // its link state.
  void setSource(AgentClient& source);
  AgentClient& source() const { return *source_; }

  void sendCommand(kapfix::v1::Command command, ReplyCallback done = {}) override;
  LinkState linkState() const override;

 private:
  QPointer<AgentClient> source_;
  std::vector<QMetaObject::Connection> connections_;
};

}  // namespace kapfix::station
