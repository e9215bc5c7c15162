#include "groundstation/session/session_tracker.hpp"

namespace kapfix::station {

SessionTracker::SessionTracker(AgentClient& client, QObject* parent) : QObject(parent) {
  connect(&client, &AgentClient::telemetryReceived, this,
          [this](const kapfix::v1::Telemetry& telemetry) { onHeader(telemetry.header(), true); });
  connect(&client, &AgentClient::stateReceived, this,
          [this](const kapfix::v1::AgentState& state) { onHeader(state.header(), false); });
}

void SessionTracker::onHeader(const kapfix::v1::Header& header, bool sequenced) {
  const std::uint64_t sequence = header.sequence();
  const std::uint64_t boot_id = header.boot_id();
  const QString agent_id = QString::fromStdString(header.agent_id());
  // A state without a boot id (an older agent's, or one inside a reply whose header was not
  // stamped) says nothing about the session: the telemetry decides.
  if (!sequenced && boot_id == 0) return;
  const bool first = session_ == 0;
  bool restarted = !first && !agent_id.isEmpty() && agent_id != agent_id_;
  if (boot_id != 0) {
    // The boot id decides: the sequence may start again for other reasons (a replay).
    restarted = restarted || (!first && boot_id != boot_id_);
    boot_id_ = boot_id;
  } else {
    // No boot id: a telemetry sequence that does not go up is a new agent process (a lost
    // message only skips ahead).
    restarted = restarted || (!first && sequence != 0 && sequence <= last_sequence_);
  }
  if (sequenced && sequence != 0) last_sequence_ = sequence;
  if (!agent_id.isEmpty()) agent_id_ = agent_id;
  if (!first && !restarted) return;
  ++session_;
  if (restarted) ++restarts_;
  emit sessionStarted(session_, restarted);
}

}  // namespace kapfix::station
