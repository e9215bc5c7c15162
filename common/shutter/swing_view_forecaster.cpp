#include "common/shutter/swing_view_forecaster.hpp"

#include <algorithm>
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
  double pan_modulus = 0, tilt_modulus = 0;
  const auto pan = Ar2PeriodFrames(pan_.coefficients(), kMinResonance, &pan_modulus);
  const auto tilt = Ar2PeriodFrames(tilt_.coefficients(), kMinResonance, &tilt_modulus);
  if (pan && (!tilt || pan_modulus >= tilt_modulus)) {
    period_ = pan;
  } else if (tilt) {
    period_ = tilt;
  }
  if (!frame.trusted) {
    // An untrusted match is no measurement; the predictors bridge a few frames or forget.
    x_.AddMissing();
    y_.AddMissing();
    expected_next_.reset();
    previous_trusted_ = false;
    return;
  }
  offsets_.push_back(frame.offset_px);
  follows_.push_back(previous_trusted_);
  previous_trusted_ = true;
  while (static_cast<int>(offsets_.size()) > error_frames_) {
    offsets_.pop_front();
    follows_.pop_front();
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

cv::Point2d SwingViewForecaster::reversion() const {
  if (offsets_.empty()) return {1, 1};
  cv::Point2d mean(0, 0);
  for (const cv::Point2d& o : offsets_) mean += o;
  mean *= 1.0 / static_cast<double>(offsets_.size());
  cv::Point2d lagged(0, 0), squares(0, 0);
  for (std::size_t i = 1; i < offsets_.size(); ++i) {
    if (!follows_[i]) continue;
    const cv::Point2d before = offsets_[i - 1] - mean, now = offsets_[i] - mean;
    lagged += cv::Point2d(before.x * now.x, before.y * now.y);
    squares += cv::Point2d(before.x * before.x, before.y * before.y);
  }
  // No spread to regress on: nothing is known of the reversion, so none is assumed.
  const auto rate = [](double l, double q) { return q > 0 ? std::clamp(l / q, 0.0, 1.0) : 1.0; };
  return {rate(lagged.x, squares.x), rate(lagged.y, squares.y)};
}

cv::Point2d SwingViewForecaster::Forecast(int frames) const {
  const cv::Point2d next(x_.Forecast(1).value_or(0.0), y_.Forecast(1).value_or(0.0));
  if (frames <= 1 || offsets_.empty()) return next;
  cv::Point2d mean(0, 0);
  for (const cv::Point2d& o : offsets_) mean += o;
  mean *= 1.0 / static_cast<double>(offsets_.size());
  const cv::Point2d rho = reversion();
  return {mean.x + std::pow(rho.x, frames - 1) * (next.x - mean.x),
          mean.y + std::pow(rho.y, frames - 1) * (next.y - mean.y)};
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

std::optional<double> SwingViewForecaster::period_frames() const { return period_; }

}  // namespace kapfix
