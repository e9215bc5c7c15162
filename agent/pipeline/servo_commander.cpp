#include "agent/pipeline/servo_commander.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <string>
#include <utility>

namespace kapfix::agent {

// Written once by the job on the worker, read by the control thread after done().
struct ServoCommander::Reopen {
  void Finish(LimitedServoDriver::BackendReopen outcome) {
    const std::lock_guard lock(mutex);
    reopened = std::move(outcome);
    finished = true;
    changed.notify_all();
  }
  bool done() {
    const std::lock_guard lock(mutex);
    return finished;
  }
  void Wait() {
    std::unique_lock lock(mutex);
    changed.wait(lock, [this] { return finished; });
  }

  std::mutex mutex;
  std::condition_variable changed;
  bool finished = false;
  LimitedServoDriver::BackendReopen reopened;
};

ServoCommander::ServoCommander(LimitedServoDriver& servos, std::mutex& mutex,
                               ServoCommanderOptions options, MonotonicClockUs clock)
    : servos_(servos),
      mutex_(mutex),
      options_(std::move(options)),
      clock_(std::move(clock)),
      held_{servos.angle(ServoAxis::kPan), servos.angle(ServoAxis::kTilt)} {}

ServoCommander::~ServoCommander() {
  if (reopen_) reopen_->Wait();
}

ServoTargets ServoCommander::Command(const ServoTargets& targets) {
  const std::int64_t now_us = clock_();
  if (out_) {
    RetryIfDue(now_us);
    if (out_) return held_;
  }
  const std::lock_guard lock(mutex_);
  {
    std::string error;
    for (const auto& [axis, deg] : {std::pair{ServoAxis::kPan, targets.pan_deg},
                                    std::pair{ServoAxis::kTilt, targets.tilt_deg}}) {
      if (servos_.SetAngle(axis, deg, &error)) continue;
      ++counters_.errors;
      // LimitedServoDriver refuses a non-finite angle itself and says why; the driver is fine.
      if (std::isfinite(deg)) {
        Fail(error, now_us);
        break;
      }
    }
  }
  held_ = {servos_.angle(ServoAxis::kPan), servos_.angle(ServoAxis::kTilt)};
  return held_;
}

void ServoCommander::Report(const DeviceHealth& health) const {
  if (options_.on_health) options_.on_health(health);
}

void ServoCommander::StartOut(const std::string& reason) {
  out_ = true;
  out_since_us_ = clock_();
  wait_ms_ = options_.retry_initial_ms;
  next_retry_us_ = out_since_us_;  // at the first command, i.e. with the first camera frame
  attempts_ = 0;
  spdlog::warn(
      "servo driver not open at start: opening it with the first camera frame, then "
      "retrying with back-off");
  out_health_ = DeviceHealth::Waiting(reason);
  Report(out_health_);
}

void ServoCommander::Fail(const std::string& error, std::int64_t now_us) {
  out_ = true;
  out_since_us_ = now_us;
  wait_ms_ = options_.retry_initial_ms;
  next_retry_us_ = now_us + std::int64_t{wait_ms_} * 1000;
  attempts_ = 0;
  ++counters_.outages;
  spdlog::error("servo driver failed: {}; the servos hold, reopening it in {} ms", error, wait_ms_);
  out_health_ = DeviceHealth::Lost(error);
  Report(out_health_);
}

void ServoCommander::RetryIfDue(std::int64_t now_us) {
  if (reopen_) {
    if (!reopen_->done()) return;  // the worker is still at it: the servos hold
    const std::shared_ptr<Reopen> finished = std::move(reopen_);
    FinishReopen(finished->reopened, now_us);
    if (out_) Report(out_health_);  // no longer reopening
    return;
  }
  if (now_us >= next_retry_us_) StartReopen(now_us);
}

void ServoCommander::StartReopen(std::int64_t now_us) {
  ++attempts_;
  {
    // From here until FinishReopen nothing reaches the backend (the watchdog's Park included),
    // so the worker may open it without this lock.
    const std::lock_guard lock(mutex_);
    servos_.Suspend();
  }
  if (!options_.worker) {
    FinishReopen(servos_.OpenBackend(), now_us);
    return;
  }
  auto reopen = std::make_shared<Reopen>();
  auto job = [reopen, &servos = servos_]() -> WorkQueue::Result {
    LimitedServoDriver::BackendReopen reopened;
    try {
      reopened = servos.OpenBackend();
    } catch (const std::exception& e) {  // a driver should not throw; the loop must not hang
      reopened.error = e.what();
    }
    reopen->Finish(std::move(reopened));
    return nullptr;  // the control thread polls the outcome in Command
  };
  std::string refused;
  if (!options_.worker->Post("servo driver reopen", std::move(job), &refused)) {
    LimitedServoDriver::BackendReopen not_run;
    not_run.error = refused;
    FinishReopen(not_run, now_us);
    return;
  }
  reopen_ = std::move(reopen);
  Report(DeviceHealth::Reopening(out_health_));
}

void ServoCommander::FinishReopen(const LimitedServoDriver::BackendReopen& reopened,
                                  std::int64_t now_us) {
  if (reopened.ok) {
    out_ = false;
    ++counters_.recoveries;
    {
      const std::lock_guard lock(mutex_);
      servos_.AdoptBackend(reopened);  // the swap, between two frames
      held_ = {servos_.angle(ServoAxis::kPan), servos_.angle(ServoAxis::kTilt)};
    }
    spdlog::info("servo driver back after {:.1f} s ({} attempts): {}",
                 static_cast<double>(now_us - out_since_us_) * 1e-6, attempts_, servos_.Describe());
    Report(DeviceHealth::Ok());
    return;
  }
  wait_ms_ = std::min(2 * wait_ms_, options_.retry_max_ms);
  next_retry_us_ = now_us + std::int64_t{wait_ms_} * 1000;
  spdlog::warn("servo driver reopen attempt {} failed: {}; next in {} ms", attempts_,
               reopened.error, wait_ms_);
}

}  // namespace kapfix::agent
