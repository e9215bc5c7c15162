#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>

namespace kapfix::agent {

// Parks the servos when the control loop stalls (config `watchdog_ms`). The control thread
// Kicks it after every step; when no Kick came for `timeout`, `on_stall` runs once on the
// watchdog's own thread (the stall may be inside the control step), and again only after
// the next Kick and another full timeout. It is armed by the first Kick, so a slow start-up
// (opening the camera, the reference frame) does not count as a stall.
class Watchdog {
 public:
  // Starts the watchdog thread. Throws std::invalid_argument for a timeout ≤ 0 or no action.
  Watchdog(std::chrono::milliseconds timeout, std::function<void()> on_stall);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

  void Kick();
  // Until the next Kick, no stall is counted (the camera is gone: nothing to control, the
  // servos hold).
  void Disarm();
  // Stops the thread (also done by the destructor); no on_stall after it returns.
  void Stop();
  std::uint64_t stall_count() const;

 private:
  void Run();

  const std::chrono::milliseconds timeout_;
  const std::function<void()> on_stall_;
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
