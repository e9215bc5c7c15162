#include "groundstation/client/link_resync.hpp"

#include <algorithm>

namespace kapfix::station {

LinkResync::LinkResync(AgentClient& client, std::int64_t station_start_us, QObject* parent)
    : QObject(parent), client_(client), station_start_us_(station_start_us) {
  connect(&client_, &AgentClient::linkChanged, this, &LinkResync::onLinkChanged);
  connect(&client_, &AgentClient::photoChunkReceived, this, [this](const kapfix::v1::Photo& chunk) {
    newest_photo_us_ = std::max(newest_photo_us_, chunk.metadata().capture_time_us());
  });
}

std::int64_t LinkResync::photosSinceUs() const {
  // One past the newest photo held: the agent resends those taken "at or after" the time.
  return newest_photo_us_ > 0 ? newest_photo_us_ + 1 : station_start_us_;
}

void LinkResync::onLinkChanged(const LinkState& state) {
  const bool up = state.up && !state.replay;
  if (up && !was_up_) {
    kapfix::v1::Command command;
    auto* request = command.mutable_request_state();
    request->set_resend_photos_since_us(photosSinceUs());
    request->set_resend_slice_report(true);
    client_.sendCommand(std::move(command));
  }
  was_up_ = up;
}

}  // namespace kapfix::station
