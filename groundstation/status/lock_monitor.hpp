#pragma once

// The lock's quality as the session goes on: feeds the telemetry into LockQuality, knows
// when the reading is stale (link down), and sounds the alert when the lock goes LOST (if
// the operator wants it). One per window; every LockIndicator shows what it says.

#include <QObject>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/status/lock_quality.hpp"

namespace kapfix::station {

class LockMonitor final : public QObject {
  Q_OBJECT

 public:
  explicit LockMonitor(AgentClient& client, LockQualityOptions options = {},
                       QObject* parent = nullptr);

  const LockReading& reading() const { return quality_.reading(); }
  // The link is down: the reading is the last one heard, not the present.
  bool stale() const { return stale_; }
  // QApplication::beep() when the verdict becomes LOST; remembered between runs.
  void setAudible(bool audible);
  bool audible() const { return audible_; }
  // [count] alerts sounded (or that would have been, when silent) since construction.
  int alerts() const { return alerts_; }
  // Forgets the old session's samples (a restarted agent is a new lock).
  void reset();

 signals:
  void changed();

 private:
  void add(const kapfix::v1::Telemetry& telemetry);

  LockQuality quality_;
  bool stale_ = false;
  bool audible_ = false;
  int alerts_ = 0;
};

}  // namespace kapfix::station
