#pragma once

// How the control loop reaches the servos, and what it does when their driver fails (issue 5:
// a servo driver error is handled like a lost camera): it says so once, clearly; it stops
// sending (the servos hold where they were last put, or where the controller's own timeout
// puts them); it reopens the driver between frames with back-off, never blocking the loop;
// and when the driver is back, fixation goes on. A non-finite target is a refusal (counted,
// nothing moves), not a driver failure.

#include <cstdint>
#include <mutex>

#include "agent/servo/limited_servo_driver.hpp"
#include "common/fixation/fixation_loop.hpp"

namespace kapfix::agent {

struct ServoCommanderOptions {
  int retry_initial_ms = 100;  // [ms] first reopen this long after the failure
  int retry_max_ms = 5000;     // [ms] doubling up to this
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

  // Sends `targets` to both axes; while the driver is out, sends nothing and reopens it when
  // the back-off allows. Returns the angles the servos were last given [deg].
  ServoTargets Command(const ServoTargets& targets);

  bool out() const { return out_; }
  Counters counters() const { return counters_; }

 private:
  void Fail(const std::string& error, std::int64_t now_us);
  void RetryIfDue(std::int64_t now_us);

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
};

}  // namespace kapfix::agent
