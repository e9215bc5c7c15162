#pragma once

// How the control loop reaches the servos, and what it does when their driver fails (issue 5:
// a servo driver error is handled like a lost camera): it says so once, clearly; it stops
// sending (the servos hold where they were last put, or where the controller's own timeout
// puts them); it reopens the driver between frames with back-off, never blocking the loop;
// and when the driver is back, fixation goes on. A non-finite target is a refusal (counted,
// nothing moves), not a driver failure.

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "agent/pipeline/device_health.hpp"
#include "agent/servo/limited_servo_driver.hpp"
#include "common/fixation/fixation_loop.hpp"

namespace kapfix::agent {

struct ServoCommanderOptions {
  int retry_initial_ms = 100;  // [ms] first reopen this long after the failure
  int retry_max_ms = 5000;     // [ms] doubling up to this
  // Reopen on a thread of its own, so that a slow one (a Maestro that does not answer: up to
  // its answer timeout; the USB setup) never holds up the control loop. Off: on the caller's
  // thread, within Command (deterministic, for tests of the back-off).
  bool reopen_in_background = true;
  // Called when the driver's health changes (out at start, failed, back), on the thread that
  // called StartOut or Command; not for a retry that fails again.
  std::function<void(const DeviceHealth&)> on_health;
};

class ServoCommander {
 public:
  struct Counters {
    std::uint64_t errors = 0;      // [count] commands that failed or were refused
    std::uint64_t outages = 0;     // [count] driver failures
    std::uint64_t recoveries = 0;  // [count] outages the driver came back from
  };

  // `mutex` guards `servos` against the watchdog's Park; both must outlive this.
  ServoCommander(LimitedServoDriver& servos, std::mutex& mutex, ServoCommanderOptions options,
                 MonotonicClockUs clock = SteadyClockNowUs);
  ~ServoCommander();  // waits for a reopen in progress
  ServoCommander(const ServoCommander&) = delete;
  ServoCommander& operator=(const ServoCommander&) = delete;

  // Sends `targets` to both axes; while the driver is out, sends nothing, takes no lock and
  // starts a reopen when the back-off allows (its outcome is taken up by a later call).
  // Returns the angles the servos were last given [deg].
  ServoTargets Command(const ServoTargets& targets);

  // The driver did not open at start (`reason`: why): the first Command opens it (then with
  // back-off), and nothing moves until it is open.
  void StartOut(const std::string& reason);

  bool out() const { return out_; }
  Counters counters() const { return counters_; }

 private:
  void Fail(const std::string& error, std::int64_t now_us);
  void RetryIfDue(std::int64_t now_us);
  void FinishReopen(std::int64_t now_us);
  void Report(const DeviceHealth& health) const;

  LimitedServoDriver& servos_;
  std::mutex& mutex_;
  const ServoCommanderOptions options_;
  MonotonicClockUs clock_;
  bool out_ = false;
  std::int64_t out_since_us_ = 0;
  std::int64_t next_retry_us_ = 0;
  int wait_ms_ = 0;
  int attempts_ = 0;
  Counters counters_;
  ServoTargets held_;
  // The reopen in progress: written by its thread before reopen_done_ is set.
  std::thread reopen_thread_;
  bool reopen_running_ = false;
  std::atomic<bool> reopen_done_{false};
  bool reopen_ok_ = false;
  std::string reopen_error_;
};

}  // namespace kapfix::agent
