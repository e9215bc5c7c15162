#include "common/shutter/swing_view_forecaster.hpp"

#include <cmath>
#include <numbers>

namespace kapfix {
namespace {

SwingPredictorOptions OneStep() {
  SwingPredictorOptions options;
  options.lead_frames = 1;
  return options;
}

}  // namespace

std::optional<double> Ar2PeriodFrames(const std::vector<double>& coefficients, double min_modulus,
                                      double* modulus) {
  // a_1, a_2, c: at least an AR(2) fit.
  if (coefficients.size() < 3) return std::nullopt;
  const double a1 = coefficients[0], a2 = coefficients[1];
  // z² − a_1 z − a_2 = 0 has complex roots when a_1² + 4 a_2 < 0, of modulus √(−a_2).
  const double discriminant = a1 * a1 + 4 * a2;
  if (!(discriminant < 0)) return std::nullopt;
  const double r = std::sqrt(-a2);
  if (modulus) *modulus = r;
  if (r < min_modulus) return std::nullopt;
  const double omega = std::atan2(std::sqrt(-discriminant), a1);  // [rad/frame] in (0, π)
  if (!(omega > 0)) return std::nullopt;
  return 2 * std::numbers::pi / omega;
}

SwingViewForecaster::SwingViewForecaster(int error_frames)
    : x_(OneStep()),
      y_(OneStep()),
      pan_(OneStep()),
      tilt_(OneStep()),
      error_frames_(error_frames < 1 ? 1 : error_frames) {}

void SwingViewForecaster::Observe(const ShutterFrame& frame) {
  pan_.Add(frame.pan_deg);
  tilt_.Add(frame.tilt_deg);
  if (!frame.trusted) {
    // An untrusted match is no measurement; the predictors bridge a few frames or forget.
    x_.AddMissing();
    y_.AddMissing();
    expected_next_.reset();
    return;
  }
  if (expected_next_) {
    errors_.push_back(frame.offset_px - *expected_next_);
    while (static_cast<int>(errors_.size()) > error_frames_) errors_.pop_front();
  }
  x_.Add(frame.offset_px.x);
  y_.Add(frame.offset_px.y);
  const auto fx = x_.Forecast(1), fy = y_.Forecast(1);
  if (fx && fy) {
    expected_next_ = cv::Point2d(*fx, *fy);
  } else {
    expected_next_.reset();
  }
}

bool SwingViewForecaster::trained() const {
  return x_.has_model() && y_.has_model() && static_cast<int>(errors_.size()) >= kMinErrorSamples;
}

cv::Point2d SwingViewForecaster::Forecast(int frames) const {
  return {x_.Forecast(frames).value_or(0.0), y_.Forecast(frames).value_or(0.0)};
}

cv::Point2d SwingViewForecaster::error_rms() const {
  if (errors_.empty()) return {0, 0};
  double sx = 0, sy = 0;
  for (const cv::Point2d& e : errors_) {
    sx += e.x * e.x;
    sy += e.y * e.y;
  }
  const auto n = static_cast<double>(errors_.size());
  return {std::sqrt(sx / n), std::sqrt(sy / n)};
}

std::optional<double> SwingViewForecaster::period_frames() const {
  double pan_modulus = 0, tilt_modulus = 0;
  const auto pan = Ar2PeriodFrames(pan_.coefficients(), kMinResonance, &pan_modulus);
  const auto tilt = Ar2PeriodFrames(tilt_.coefficients(), kMinResonance, &tilt_modulus);
  if (pan && (!tilt || pan_modulus >= tilt_modulus)) return pan;
  return tilt;
}

}  // namespace kapfix
