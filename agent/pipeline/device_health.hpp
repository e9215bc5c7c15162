#pragma once

// Whether the camera and the servo controller are there (issue 10: the agent starts with
// whatever is there and waits for the rest). The pipeline keeps the one copy; the service
// manager's status, AgentState and every Telemetry are made from it.

#include <cstddef>
#include <string>
#include <string_view>

namespace kapfix::agent {

enum class DeviceStatus {
  kOk,       // open and working
  kWaiting,  // not there since the start: opened again with back-off
  kLost,     // was working, failed: reopened with back-off
};

// [bytes] the longest reason kept: enough for a path and an errno text, small enough to ride
// along every Telemetry message.
inline constexpr std::size_t kMaxDeviceReasonBytes = 160;

// What a device's reason starts with while it is being reopened.
inline constexpr std::string_view kReopeningPrefix = "reopening after: ";

struct DeviceHealth {
  DeviceStatus status = DeviceStatus::kOk;
  std::string
      reason;  // why it is not OK, cut to kMaxDeviceReasonBytes of valid UTF-8; empty when OK

  static DeviceHealth Ok() { return {}; }
  static DeviceHealth Waiting(std::string_view reason);
  static DeviceHealth Lost(std::string_view reason);
  // `out` (waiting or lost) while a reopen attempt runs on the worker: the same status, the
  // reason led by kReopeningPrefix, so that the station and systemctl status say it.
  static DeviceHealth Reopening(const DeviceHealth& out);
  bool reopening() const;
  bool operator==(const DeviceHealth&) const = default;
};

struct DevicesHealth {
  DeviceHealth camera;
  DeviceHealth servos;
  bool operator==(const DevicesHealth&) const = default;
};

// `text` as valid UTF-8 (an invalid byte becomes '?': a link message must carry valid UTF-8)
// of at most `max_bytes`, cut on a character boundary.
std::string BoundedUtf8(std::string_view text, std::size_t max_bytes);

// "ok", "waiting", "lost".
std::string_view DeviceStatusWord(DeviceStatus status);

// One line for systemctl status: "camera waiting: <reason>; servos ok".
std::string StatusLine(const DevicesHealth& health);

}  // namespace kapfix::agent
