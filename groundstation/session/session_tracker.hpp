#pragma once

// Which agent session the station is looking at (issue 14): a restarted agent is a new
// session, whose panels must not mix with the old one's. The link reconnects by itself and
// says nothing about a restart, so it is read from the telemetry: its header.sequence starts
// again at 1 in a new agent process (header.proto: strictly increasing per sender and
// stream), and the agent id may change.
//
// TODO(issue 14): replace the sequence heuristic by the agent's boot id once AgentState and
// Header carry one (a `boot_id` field in header.proto, set once per agent process).

#include <QDateTime>
#include <QObject>
#include <QString>
#include <cstdint>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class SessionTracker final : public QObject {
  Q_OBJECT

 public:
  explicit SessionTracker(AgentClient& client, QObject* parent = nullptr);

  // [count] 0 until the agent was first heard, then 1, 2, ... one per agent process seen.
  int session() const { return session_; }
  // [count] sessions that began with a restart (not the first one heard).
  int restarts() const { return restarts_; }

 signals:
  // A new session began. `restart`: an agent was already heard in this station's run, so
  // the one now talking was restarted (or replaced) and knows nothing of the old session.
  void sessionStarted(int session, bool restart);

 private:
  void onTelemetry(const kapfix::v1::Telemetry& telemetry);

  int session_ = 0;
  int restarts_ = 0;
  std::uint64_t last_sequence_ = 0;  // [count] telemetry header.sequence last seen
  QString agent_id_;
};

}  // namespace kapfix::station
