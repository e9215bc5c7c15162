#pragma once

// How the control loop reaches the servos, and what it does when their driver fails (issue 5:
// a servo driver error is handled like a lost camera): it says so once, clearly; it stops
// sending (the servos hold where they were last put, or where the controller's own timeout
// puts them); it reopens the driver with back-off on the worker (issue 11: the control thread
// never waits; a reopen may block on USB or I2C for hundreds of ms), meanwhile the loop goes on
// and the health says "reopening"; the reopened driver is taken up by the first command after
// the reopen finished, i.e. between two frames; and fixation goes on. A non-finite target is a
// refusal (counted, nothing moves), not a driver failure.

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "agent/pipeline/device_health.hpp"
#include "agent/servo/limited_servo_driver.hpp"
#include "agent/worker/work_queue.hpp"
#include "common/fixation/fixation_loop.hpp"

namespace kapfix::agent {

struct ServoCommanderOptions {
  int retry_initial_ms = 100;  // [ms] first reopen this long after the failure
  int retry_max_ms = 5000;     // [ms] doubling up to this
  // Where the reopen runs: a job on this queue, its outcome taken up by the first Command
  // after it finished. None: within Command, on the caller's thread (deterministic, for tests
  // of the back-off).
  std::shared_ptr<WorkQueue> worker;
  // Called when the driver's health changes (out at start, failed, reopening on the worker,
  // back; a failed reopen: out again), on the thread that called StartOut or Command.
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
  ~ServoCommander();  // waits for a reopen in progress (it uses the driver)
  ServoCommander(const ServoCommander&) = delete;
  ServoCommander& operator=(const ServoCommander&) = delete;

  // Sends `targets` to both axes; while the driver is out, sends nothing and starts a reopen
  // when the back-off allows (its outcome is taken up by a later call); never waits for the
  // device while a worker reopens it.
  // Returns the angles the servos were last given [deg].
  ServoTargets Command(const ServoTargets& targets);

  // The driver did not open at start (`reason`: why): the first Command opens it (then with
  // back-off), and nothing moves until it is open.
  void StartOut(const std::string& reason);

  bool out() const { return out_; }
  Counters counters() const { return counters_; }

 private:
  struct Reopen;  // a reopen in progress, shared with its job

  void Fail(const std::string& error, std::int64_t now_us);
  void RetryIfDue(std::int64_t now_us);
  void StartReopen(std::int64_t now_us);
  void FinishReopen(const LimitedServoDriver::BackendReopen& reopened, std::int64_t now_us);
  void Report(const DeviceHealth& health) const;

  LimitedServoDriver& servos_;
  std::mutex& mutex_;
  const ServoCommanderOptions options_;
  MonotonicClockUs clock_;
  bool out_ = false;
  DeviceHealth out_health_;  // as reported when the driver went out
  std::int64_t out_since_us_ = 0;
  std::int64_t next_retry_us_ = 0;
  int wait_ms_ = 0;
  int attempts_ = 0;
  Counters counters_;
  ServoTargets held_;
  std::shared_ptr<Reopen> reopen_;  // the reopen on the worker, if one runs
};

}  // namespace kapfix::agent
