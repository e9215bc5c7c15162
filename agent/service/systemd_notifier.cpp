#include "agent/service/systemd_notifier.hpp"

#include <systemd/sd-daemon.h>

#include <chrono>

#include "common/time/steady_clock.hpp"

namespace kapfix::agent {

SystemdNotifier::SystemdNotifier() {
  std::uint64_t usec = 0;
  // 0 (no watchdog asked for) leaves usec at 0; > 0 gives WatchdogSec in µs.
  if (sd_watchdog_enabled(0, &usec) > 0) interval_us_ = usec / 4;
}

void SystemdNotifier::Ready(const std::string& status) {
  sd_notifyf(0, "READY=1\nSTATUS=%s", status.c_str());
}

void SystemdNotifier::Alive() {
  if (interval_us_ == 0) return;
  const std::int64_t now = SteadyClockNowUs();
  std::int64_t last = last_us_.load();
  if (now - last < static_cast<std::int64_t>(interval_us_)) return;
  if (!last_us_.compare_exchange_strong(last, now)) return;  // another thread just sent it
  sd_notify(0, "WATCHDOG=1");
}

void SystemdNotifier::Status(const std::string& status) {
  sd_notifyf(0, "STATUS=%s", status.c_str());
}

void SystemdNotifier::Stopping() { sd_notify(0, "STOPPING=1"); }

}  // namespace kapfix::agent
