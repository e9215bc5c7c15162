#pragma once

#include <atomic>
#include <cstdint>
#include <string>

namespace kapfix::agent {

// The agent's side of systemd's Type=notify and WatchdogSec (deploy/kapfix-agent.service):
// Ready() once the link is up, Alive() from the control loop and from the camera's reconnect
// waits. Alive sends WATCHDOG=1 at most every quarter of the unit's watchdog period, so it is
// cheap to call every frame. Outside systemd (no NOTIFY_SOCKET) every call does nothing.
// Thread-safe.
class SystemdNotifier {
 public:
  SystemdNotifier();

  void Ready(const std::string& status);
  void Alive();
  void Status(const std::string& status);  // STATUS=…, shown by systemctl status
  void Stopping();

  bool watchdog_enabled() const { return interval_us_ > 0; }

 private:
  std::uint64_t interval_us_ = 0;  // [µs] a quarter of WatchdogSec; 0 = no watchdog
  std::atomic<std::int64_t> last_us_{0};
};

}  // namespace kapfix::agent
