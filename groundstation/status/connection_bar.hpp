#pragma once

// Which agent to talk to: host and ports (SPEC §5 defaults), remembered between runs. The
// link reconnects by itself; "Connect" is only for choosing another agent.

#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QWidget>

#include "groundstation/client/agent_address.hpp"

namespace kapfix::station {

class ZmqAgentClient;

class ConnectionBar final : public QWidget {
  Q_OBJECT

 public:
  explicit ConnectionBar(ZmqAgentClient& client, QWidget* parent = nullptr);

  AgentAddress address() const;
  // Connects to what the fields say and remembers it; false (with the reason shown) when
  // the address is not usable.
  bool connectToAgent();
  void setAddress(const AgentAddress& address);
  QLineEdit& hostEdit() const { return *host_; }

 private:
  ZmqAgentClient& client_;
  QLineEdit* host_;
  QSpinBox* command_port_;
  QSpinBox* stream_port_;
  QPushButton* connect_;
};

}  // namespace kapfix::station
