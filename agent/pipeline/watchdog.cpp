#include "agent/pipeline/watchdog.hpp"

#include <algorithm>
#include <stdexcept>

namespace kapfix::agent {

Watchdog::Watchdog(std::chrono::milliseconds timeout, std::function<void()> on_stall,
                   WatchdogClock clock)
    : timeout_(timeout), on_stall_(std::move(on_stall)), clock_(std::move(clock)) {
  if (timeout_.count() <= 0) throw std::invalid_argument("Watchdog: timeout must be > 0 ms");
  if (!on_stall_) throw std::invalid_argument("Watchdog: no action on a stall");
  if (!clock_) throw std::invalid_argument("Watchdog: no clock");
  thread_ = std::thread([this] { Run(); });
}

Watchdog::~Watchdog() { Stop(); }

void Watchdog::Kick() {
  const auto now = clock_();
  std::lock_guard lock(mutex_);
  last_kick_ = now;
  armed_ = true;
  fired_ = false;
}

void Watchdog::Disarm() {
  std::lock_guard lock(mutex_);
  armed_ = false;
}

void Watchdog::Check() {
  std::unique_lock lock(mutex_);
  if (!stop_ && UntilDue() <= std::chrono::steady_clock::duration::zero()) Fire(lock);
}

void Watchdog::Stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::uint64_t Watchdog::stall_count() const {
  std::lock_guard lock(mutex_);
  return stalls_;
}

std::chrono::steady_clock::duration Watchdog::UntilDue() const {
  // The clock is read on every look, armed or not, so that a test can tell the watchdog
  // looked.
  const auto now = clock_();
  // Nothing to watch until the next Kick: look again at the timeout's pace.
  if (!armed_ || fired_) return timeout_;
  const std::chrono::steady_clock::duration left = last_kick_ + timeout_ - now;
  return std::clamp<std::chrono::steady_clock::duration>(
      left, std::chrono::steady_clock::duration::zero(), timeout_);
}

void Watchdog::Fire(std::unique_lock<std::mutex>& lock) {
  fired_ = true;
  ++stalls_;
  lock.unlock();
  on_stall_();
  lock.lock();
}

void Watchdog::Run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    const auto wait = UntilDue();
    if (wait > std::chrono::steady_clock::duration::zero()) {
      wake_.wait_for(lock, wait, [this] { return stop_; });
      continue;
    }
    Fire(lock);
  }
}

}  // namespace kapfix::agent
