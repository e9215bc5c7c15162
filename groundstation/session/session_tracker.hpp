#pragma once

// Which agent session the station is looking at (issue 14): a restarted agent is a new
// session, whose panels must not mix with the old one's. The link reconnects by itself and
// says nothing about a restart; the agent's messages do. Each agent process draws a random
// boot id once (header.boot_id): a different non-zero boot id is a new process. An older
// agent sends none (0); then the telemetry's header.sequence tells, since it starts again at
// 1 in a new process (header.proto: strictly increasing per sender and stream). A different
// agent id is a new session either way.

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
  // The current session's boot id; 0 when its agent sends none.
  std::uint64_t bootId() const { return boot_id_; }

 signals:
  // A new session began. `restart`: an agent was already heard in this station's run, so
  // the one now talking was restarted (or replaced) and knows nothing of the old session.
  void sessionStarted(int session, bool restart);

 private:
  // `sequenced`: the header's sequence belongs to the telemetry stream, the one whose
  // numbering is followed when there is no boot id.
  void onHeader(const kapfix::v1::Header& header, bool sequenced);

  int session_ = 0;
  int restarts_ = 0;
  std::uint64_t last_sequence_ = 0;  // [count] telemetry header.sequence last seen
  std::uint64_t boot_id_ = 0;        // last non-zero boot id heard
  QString agent_id_;
};

}  // namespace kapfix::station
