#include "common/sim/simulated_servo.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

constexpr int kMaxLatencyFrames = 1000;
constexpr std::uint64_t kLatencyStream = 0x6c6174;  // "lat"

}  // namespace

bool SimulatedServoOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!std::isfinite(min_deg) || !std::isfinite(max_deg) || !(min_deg < max_deg)) {
    return fail("servo limits must be finite with min < max, got [" + std::to_string(min_deg) +
                ", " + std::to_string(max_deg) + "] deg");
  }
  if (!std::isfinite(rate_limit_deg_per_frame) || rate_limit_deg_per_frame <= 0) {
    return fail("servo rate limit must be > 0 deg/frame, got " +
                std::to_string(rate_limit_deg_per_frame));
  }
  if (!std::isfinite(dead_band_deg) || dead_band_deg < 0) {
    return fail("servo dead band must be ≥ 0 deg, got " + std::to_string(dead_band_deg));
  }
  if (!std::isfinite(backlash_deg) || backlash_deg < 0) {
    return fail("servo backlash must be ≥ 0 deg, got " + std::to_string(backlash_deg));
  }
  if (latency_frames < 0 || latency_frames > kMaxLatencyFrames) {
    return fail("servo latency must be 0…" + std::to_string(kMaxLatencyFrames) + " frames, got " +
                std::to_string(latency_frames));
  }
  if (latency_max_frames != 0 &&
      (latency_max_frames < latency_frames || latency_max_frames > kMaxLatencyFrames)) {
    return fail("servo latency jitter must reach latency (" + std::to_string(latency_frames) +
                ")…" + std::to_string(kMaxLatencyFrames) + " frames, got " +
                std::to_string(latency_max_frames));
  }
  if (!(initial_deg >= min_deg && initial_deg <= max_deg)) {
    return fail("servo initial angle " + std::to_string(initial_deg) +
                " deg is outside its limits");
  }
  return true;
}

SimulatedServo::SimulatedServo(SimulatedServoOptions options)
    : options_(options),
      target_(options.initial_deg),
      shaft_(options.initial_deg),
      output_(options.initial_deg),
      commanded_(options.initial_deg) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("SimulatedServo: " + error);
}

void SimulatedServo::Command(double target_deg) {
  if (std::isnan(target_deg)) return;
  commanded_ = std::clamp(target_deg, options_.min_deg, options_.max_deg);
  pending_.push_back({steps_ + Latency(), commanded_, issued_++});
}

int SimulatedServo::Latency() const {
  const int low = options_.latency_frames, high = options_.latency_max_frames;
  if (high <= low) return low;
  const double u = SimUniform(options_.seed, kLatencyStream, issued_);
  return low + std::min(high - low, static_cast<int>(u * (high - low + 1)));
}

double SimulatedServo::Step() {
  // The newest command that has arrived wins; older ones still in flight are obsolete.
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (it->active_at_step <= steps_) {
      if (it->issued > active_issued_) {
        target_ = it->target_deg;
        active_issued_ = it->issued;
      }
      it = pending_.erase(it);
    } else if (it->issued < active_issued_) {
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
  ++steps_;

  const double error = target_ - shaft_;
  if (std::abs(error) >= options_.dead_band_deg && error != 0.0) {
    const double rate = options_.rate_limit_deg_per_frame;
    shaft_ =
        std::clamp(shaft_ + std::clamp(error, -rate, rate), options_.min_deg, options_.max_deg);
  }
  // Play operator: the output moves only when the shaft pushes against one side of the gap.
  const double half_gap = options_.backlash_deg / 2.0;
  output_ = std::clamp(output_, shaft_ - half_gap, shaft_ + half_gap);
  output_ = std::clamp(output_, options_.min_deg, options_.max_deg);
  return output_;
}

}  // namespace kapfix
