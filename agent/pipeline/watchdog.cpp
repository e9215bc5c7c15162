#include "agent/pipeline/watchdog.hpp"

#include <stdexcept>

namespace kapfix::agent {

Watchdog::Watchdog(std::chrono::milliseconds timeout, std::function<void()> on_stall)
    : timeout_(timeout), on_stall_(std::move(on_stall)) {
  if (timeout_.count() <= 0) throw std::invalid_argument("Watchdog: timeout must be > 0 ms");
  if (!on_stall_) throw std::invalid_argument("Watchdog: no action on a stall");
  thread_ = std::thread([this] { Run(); });
}

Watchdog::~Watchdog() { Stop(); }

void Watchdog::Kick() {
  std::lock_guard lock(mutex_);
  last_kick_ = std::chrono::steady_clock::now();
  armed_ = true;
  fired_ = false;
}

void Watchdog::Disarm() {
  std::lock_guard lock(mutex_);
  armed_ = false;
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

void Watchdog::Run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    if (!armed_ || fired_) {
      // Nothing to watch until the next Kick; poll at the timeout's pace.
      wake_.wait_for(lock, timeout_, [this] { return stop_; });
      continue;
    }
    const auto deadline = last_kick_ + timeout_;
    if (wake_.wait_until(lock, deadline, [this] { return stop_; })) break;
    if (!fired_ && std::chrono::steady_clock::now() >= last_kick_ + timeout_) {
      fired_ = true;
      ++stalls_;
      lock.unlock();
      on_stall_();
      lock.lock();
    }
  }
}

}  // namespace kapfix::agent
