#include "groundstation/client/switchable_agent_client.hpp"

#include <utility>

namespace kapfix::station {

SwitchableAgentClient::SwitchableAgentClient(AgentClient& source, QObject* parent)
    : AgentClient(parent) {
  setSource(source);
}

void SwitchableAgentClient::setSource(AgentClient& source) {
  for (const auto& connection : connections_) disconnect(connection);
  connections_.clear();
  source_ = &source;
  // Signal to signal: each arrives here on the GUI thread and is re-emitted at once.
  connections_ = {
      connect(&source, &AgentClient::linkChanged, this, &AgentClient::linkChanged),
      connect(&source, &AgentClient::telemetryReceived, this, &AgentClient::telemetryReceived),
      connect(&source, &AgentClient::videoFrameReceived, this, &AgentClient::videoFrameReceived),
      connect(&source, &AgentClient::sliceReportReceived, this, &AgentClient::sliceReportReceived),
      connect(&source, &AgentClient::pssReportReceived, this, &AgentClient::pssReportReceived),
      connect(&source, &AgentClient::calibrationReceived, this, &AgentClient::calibrationReceived),
      connect(&source, &AgentClient::stateReceived, this, &AgentClient::stateReceived),
      connect(&source, &AgentClient::photoChunkReceived, this, &AgentClient::photoChunkReceived),
      connect(&source, &AgentClient::logReceived, this, &AgentClient::logReceived),
      connect(&source, &AgentClient::commandSent, this, &AgentClient::commandSent),
      connect(&source, &AgentClient::replyReceived, this, &AgentClient::replyReceived),
      connect(&source, &AgentClient::messageReceived, this, &AgentClient::messageReceived),
  };
  emit linkChanged(source.linkState());
}

void SwitchableAgentClient::sendCommand(kapfix::v1::Command command, ReplyCallback done) {
  if (source_.isNull()) {
    CommandOutcome outcome;
    outcome.reason = tr("no agent");
    QMetaObject::invokeMethod(
        this,
        [outcome, done = std::move(done)] {
          if (done) done(outcome);
        },
        Qt::QueuedConnection);
    return;
  }
  source_->sendCommand(std::move(command), std::move(done));
}

LinkState SwitchableAgentClient::linkState() const {
  return source_.isNull() ? LinkState{} : source_->linkState();
}

}  // namespace kapfix::station
