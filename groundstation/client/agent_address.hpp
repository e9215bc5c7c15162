#pragma once

// Where an agent listens (SPEC §5 defaults: commands on 5555, streams on 5556, localhost),
// remembered between runs.

#include <QSettings>
#include <QString>

namespace kapfix::station {

struct AgentAddress {
  QString host = QStringLiteral("localhost");
  int command_port = 5555;  // [TCP port] the agent's ROUTER
  int stream_port = 5556;   // [TCP port] the agent's PUB

  QString commandEndpoint() const;  // "tcp://host:5555"
  QString streamEndpoint() const;   // "tcp://host:5556"

  // Under "agent/" in `settings`; defaults for whatever is missing.
  static AgentAddress load(const QSettings& settings);
  void save(QSettings& settings) const;

  bool operator==(const AgentAddress&) const = default;
};

}  // namespace kapfix::station
