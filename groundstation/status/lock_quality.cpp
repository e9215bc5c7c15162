#include "groundstation/status/lock_quality.hpp"

#include <cmath>
#include <cstdio>

namespace kapfix::station {
namespace {

bool Tracking(kapfix::v1::Mode mode) {
  return mode == kapfix::v1::MODE_FIXATE || mode == kapfix::v1::MODE_FOLLOW;
}

}  // namespace

bool LockQualityOptions::IsValid(std::string* error) const {
  const auto fail = [error](const char* why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (!(window_s > 0)) return fail("lock quality: window_s must be > 0 s");
  if (!(confidence_window_s > 0) || confidence_window_s > window_s) {
    return fail("lock quality: confidence_window_s must be in (0, window_s]");
  }
  if (!(degraded_confidence >= 0 && degraded_confidence <= 1)) {
    return fail("lock quality: degraded_confidence must be in [0, 1]");
  }
  if (!(degraded_rms_px > 0) || !(lost_rms_px > degraded_rms_px)) {
    return fail("lock quality: need 0 < degraded_rms_px < lost_rms_px");
  }
  return true;
}

LockQuality::LockQuality(LockQualityOptions options) : options_(options) {}

void LockQuality::reset() {
  samples_.clear();
  sum_sq_ = 0;
  mode_ = kapfix::v1::MODE_UNSPECIFIED;
  reading_ = LockReading{};
}

const LockReading& LockQuality::add(const kapfix::v1::Telemetry& telemetry) {
  // A new mode is a new lock: what was measured before says nothing about it.
  if (telemetry.mode() != mode_) {
    samples_.clear();
    sum_sq_ = 0;
    mode_ = telemetry.mode();
  }
  const std::int64_t now_us = telemetry.header().capture_time_us();
  // Capture time going back means a restarted or replayed source: start the window again.
  if (!samples_.empty() && now_us < samples_.back().capture_us) {
    samples_.clear();
    sum_sq_ = 0;
  }
  const auto& d = telemetry.displacement();
  const double x = d.x_px() + static_cast<double>(d.x_subpx());
  const double y = d.y_px() + static_cast<double>(d.y_subpx());
  const double residual_sq = x * x + y * y;
  samples_.push_back({now_us, residual_sq, static_cast<double>(telemetry.confidence())});
  sum_sq_ += residual_sq;
  const auto window_us = static_cast<std::int64_t>(options_.window_s * 1e6);
  while (samples_.front().capture_us < now_us - window_us) {
    sum_sq_ -= samples_.front().residual_sq;
    samples_.pop_front();
  }
  sum_sq_ = std::max(0.0, sum_sq_);  // rounding of the running sum

  const auto confidence_us = static_cast<std::int64_t>(options_.confidence_window_s * 1e6);
  double confidence_sum = 0;
  int confidence_count = 0;
  for (auto it = samples_.rbegin(); it != samples_.rend(); ++it) {
    if (it->capture_us < now_us - confidence_us) break;
    confidence_sum += it->confidence;
    ++confidence_count;
  }

  reading_.residual_px = std::sqrt(residual_sq);
  reading_.rms_px = std::sqrt(sum_sq_ / static_cast<double>(samples_.size()));
  reading_.confidence = confidence_sum / std::max(1, confidence_count);
  reading_.off_target = Tracking(mode_) && !telemetry.lock_lost() && telemetry.off_target();
  if (!Tracking(mode_)) {
    reading_.verdict = LockVerdict::kNone;
  } else if (telemetry.lock_lost() || reading_.rms_px > options_.lost_rms_px) {
    reading_.verdict = LockVerdict::kLost;
  } else if (telemetry.off_target() || reading_.confidence < options_.degraded_confidence ||
             reading_.rms_px > options_.degraded_rms_px) {
    reading_.verdict = LockVerdict::kDegraded;
  } else {
    reading_.verdict = LockVerdict::kLocked;
  }
  reading_.calibration.clear();
  if (Tracking(mode_) && telemetry.has_deg_per_px()) {
    const auto& e = telemetry.deg_per_px();
    const double sigma_pct = 100.0 * e.pan_uncertainty();
    char text[96];
    if (std::isfinite(sigma_pct)) {
      std::snprintf(text, sizeof text, "deg/px %.4f ±%.0f %% %s · forecast %.0f %%",
                    static_cast<double>(e.pan_deg_per_px()), sigma_pct,
                    e.trusted() ? "trusted" : "not trusted",
                    100.0 * static_cast<double>(telemetry.forecast_weight()));
    } else {
      std::snprintf(text, sizeof text, "deg/px %.4f (no fit yet) · forecast %.0f %%",
                    static_cast<double>(e.pan_deg_per_px()),
                    100.0 * static_cast<double>(telemetry.forecast_weight()));
    }
    reading_.calibration = text;
  }
  return reading_;
}

}  // namespace kapfix::station
