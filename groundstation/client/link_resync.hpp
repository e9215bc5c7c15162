#pragma once

// Catching up after the link comes (back) up: asks the agent for its full state, its latest
// SSP report, and every photo taken since the newest one this station has — so photos the
// agent saved while the link was down arrive once it is back (SPEC §4: nothing is lost).

#include <QObject>
#include <cstdint>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class LinkResync final : public QObject {
  Q_OBJECT

 public:
  // `station_start_us` [µs since epoch]: with no photo received yet, photos taken before
  // it are not asked for (they belong to earlier sessions).
  LinkResync(AgentClient& client, std::int64_t station_start_us, QObject* parent = nullptr);

  // [µs since epoch] what the next request asks photos from.
  std::int64_t photosSinceUs() const;

 private:
  void onLinkChanged(const LinkState& state);

  AgentClient& client_;
  std::int64_t station_start_us_;
  std::int64_t newest_photo_us_ = 0;  // [µs since epoch] capture time; 0 = none yet
  bool was_up_ = false;
};

}  // namespace kapfix::station
