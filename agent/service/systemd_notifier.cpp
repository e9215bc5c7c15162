#include "agent/service/systemd_notifier.hpp"

#include <systemd/sd-daemon.h>

#include <chrono>

namespace kapfix::agent {
namespace {

std::int64_t NowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

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
  const std::int64_t now = NowUs();
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
