#include "groundstation/client/agent_address.hpp"

namespace kapfix::station {

QString AgentAddress::commandEndpoint() const {
  return QStringLiteral("tcp://%1:%2").arg(host).arg(command_port);
}

QString AgentAddress::streamEndpoint() const {
  return QStringLiteral("tcp://%1:%2").arg(host).arg(stream_port);
}

AgentAddress AgentAddress::load(const QSettings& settings) {
  AgentAddress address;
  address.host = settings.value(QStringLiteral("agent/host"), address.host).toString();
  address.command_port =
      settings.value(QStringLiteral("agent/command_port"), address.command_port).toInt();
  address.stream_port =
      settings.value(QStringLiteral("agent/stream_port"), address.stream_port).toInt();
  return address;
}

void AgentAddress::save(QSettings& settings) const {
  settings.setValue(QStringLiteral("agent/host"), host);
  settings.setValue(QStringLiteral("agent/command_port"), command_port);
  settings.setValue(QStringLiteral("agent/stream_port"), stream_port);
}

}  // namespace kapfix::station
