#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

namespace kapfix::agent::testing {

// A steady clock a test moves by hand, read from any thread; it counts its readings, so a
// test can wait until a thread has looked at the time it set (an event, not a sleep).
class ManualClock {
 public:
  using time_point = std::chrono::steady_clock::time_point;

  time_point Now() {
    ++reads_;
    return time_point(std::chrono::nanoseconds(now_ns_.load()));
  }
  void Advance(std::chrono::nanoseconds step) { now_ns_ += step.count(); }
  std::uint64_t reads() const { return reads_.load(); }
  // For WatchdogClock and the like; the clock must outlive the user.
  auto AsFunction() {
    return [this] { return Now(); };
  }

 private:
  // Starts well after the epoch, like a real steady clock, so that "a timeout ago" exists.
  std::atomic<std::int64_t> now_ns_{std::int64_t{1'000'000'000'000}};
  std::atomic<std::uint64_t> reads_{0};
};

}  // namespace kapfix::agent::testing
