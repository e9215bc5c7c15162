#include "agent/pipeline/servo_commander.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace kapfix::agent {

ServoCommander::ServoCommander(LimitedServoDriver& servos, std::mutex& mutex,
                               ServoCommanderOptions options, MonotonicClockUs clock)
    : servos_(servos),
      mutex_(mutex),
      options_(std::move(options)),
      clock_(std::move(clock)),
      held_{servos.angle(ServoAxis::kPan), servos.angle(ServoAxis::kTilt)} {}

ServoCommander::~ServoCommander() {
  if (reopen_thread_.joinable()) reopen_thread_.join();
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
  Report(DeviceHealth::Waiting(reason));
}

void ServoCommander::Fail(const std::string& error, std::int64_t now_us) {
  out_ = true;
  out_since_us_ = now_us;
  wait_ms_ = options_.retry_initial_ms;
  next_retry_us_ = now_us + std::int64_t{wait_ms_} * 1000;
  attempts_ = 0;
  ++counters_.outages;
  spdlog::error("servo driver failed: {}; the servos hold, reopening it in {} ms", error, wait_ms_);
  Report(DeviceHealth::Lost(error));
}

void ServoCommander::RetryIfDue(std::int64_t now_us) {
  if (reopen_running_) {
    if (reopen_done_.load(std::memory_order_acquire)) FinishReopen(now_us);
    return;
  }
  if (now_us < next_retry_us_) return;
  ++attempts_;
  reopen_running_ = true;
  reopen_done_.store(false);
  auto reopen = [this] {
    const std::lock_guard lock(mutex_);
    std::string error;
    reopen_ok_ = servos_.Reopen(&error);
    reopen_error_ = error;
    reopen_done_.store(true, std::memory_order_release);
  };
  if (options_.reopen_in_background) {
    reopen_thread_ = std::thread(reopen);
  } else {
    reopen();
    FinishReopen(now_us);
  }
}

void ServoCommander::FinishReopen(std::int64_t now_us) {
  if (reopen_thread_.joinable()) reopen_thread_.join();
  reopen_running_ = false;
  if (reopen_ok_) {
    out_ = false;
    ++counters_.recoveries;
    {
      const std::lock_guard lock(mutex_);
      held_ = {servos_.angle(ServoAxis::kPan), servos_.angle(ServoAxis::kTilt)};
    }
    spdlog::info("servo driver back after {:.1f} s ({} attempts): {}",
                 static_cast<double>(now_us - out_since_us_) * 1e-6, attempts_, servos_.Describe());
    Report(DeviceHealth::Ok());
    return;
  }
  wait_ms_ = std::min(2 * wait_ms_, options_.retry_max_ms);
  next_retry_us_ = now_us + std::int64_t{wait_ms_} * 1000;
  spdlog::warn("servo driver reopen attempt {} failed: {}; next in {} ms", attempts_, reopen_error_,
               wait_ms_);
}

}  // namespace kapfix::agent
