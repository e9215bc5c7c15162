#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

namespace kapfix::agent {

// The watchdog's time: std::chrono::steady_clock in flight; a test moves its own.
using WatchdogClock = std::function<std::chrono::steady_clock::time_point()>;

// Parks the servos when the control loop stalls (config `watchdog_ms`). The control thread
// Kicks it after every step; when no Kick came for `timeout`, `on_stall` runs once on the
// watchdog's own thread (the stall may be inside the control step), and again only after
// the next Kick and another full timeout. It is armed by the first Kick, so a slow start-up
// (opening the camera, the reference frame) does not count as a stall.
class Watchdog {
 public:
  // Starts the watchdog thread. Throws std::invalid_argument for a timeout ≤ 0 or no action.
  Watchdog(std::chrono::milliseconds timeout, std::function<void()> on_stall,
           WatchdogClock clock = std::chrono::steady_clock::now);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void Kick();
  // Until the next Kick, no stall is counted (the camera is gone: nothing to control, the
  // servos hold).
  void Disarm();
  // Runs on_stall now (on the caller's thread) when the clock says a stall is due. The
  // watchdog's thread calls it at every deadline and at least once per timeout; a test that
  // moves the clock calls it to see the outcome at once.
  void Check();
  // Stops the thread (also done by the destructor); no on_stall after it returns.
  void Stop();
  std::uint64_t stall_count() const;

 private:
  void Run();
  // With mutex_ held: how long until the next look at the clock (≤ timeout_), zero when a
  // stall is due now.
  std::chrono::steady_clock::duration UntilDue() const;
  void Fire(std::unique_lock<std::mutex>& lock);

  const std::chrono::milliseconds timeout_;
  const std::function<void()> on_stall_;
  const WatchdogClock clock_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::chrono::steady_clock::time_point last_kick_;
  bool armed_ = false;
  bool fired_ = false;
  bool stop_ = false;
  std::uint64_t stalls_ = 0;
  std::thread thread_;
};

}  // namespace kapfix::agent
