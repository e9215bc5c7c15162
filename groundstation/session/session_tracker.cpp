#include "groundstation/session/session_tracker.hpp"

namespace kapfix::station {

SessionTracker::SessionTracker(AgentClient& client, QObject* parent) : QObject(parent) {
  connect(&client, &AgentClient::telemetryReceived, this, &SessionTracker::onTelemetry);
}

void SessionTracker::onTelemetry(const kapfix::v1::Telemetry& telemetry) {
  const std::uint64_t sequence = telemetry.header().sequence();
  const QString agent_id = QString::fromStdString(telemetry.header().agent_id());
  const bool first = session_ == 0;
  // A sequence that does not go up is a new agent process (a lost message only skips ahead).
  const bool restarted =
      !first && ((sequence != 0 && sequence <= last_sequence_) || agent_id != agent_id_);
  if (sequence != 0) last_sequence_ = sequence;
  agent_id_ = agent_id;
  if (!first && !restarted) return;
  ++session_;
  if (restarted) ++restarts_;
  emit sessionStarted(session_, restarted);
}

}  // namespace kapfix::station
