#pragma once

#include <deque>

#include "common/control/swing_predictor.hpp"
#include "common/shutter/view_forecaster.hpp"

namespace kapfix {

// ViewForecaster over SwingPredictors (through their public forecast API only):
//  - one per axis on the measured residual offset, one step ahead, which forecasts where the
//    loop will leave the view (a gust the loop has not caught up with swings on in the
//    residual, the AR model sees it);
//  - one per servo axis on the commanded angle, which follows the swing itself: its AR(2)
//    fit's complex roots r·e^{±iω} give the swing period 2π/ω (the axis with the larger r,
//    the more resonant one, wins; none below kMinResonance).
// The one-step error is measured, not assumed: each frame's offset against the forecast made
// for it one frame before, RMS over the last error_frames.
// Beyond one frame the residual is forecast as the closed loop holds it: the loop corrects
// whatever offset it measures, so the residual reverts to its recent mean m (over the last
// error_frames trusted offsets) at the rate ρ it was measured to revert at (the lag-1
// regression of its deviations from m, in [0, 1]): Forecast(k) = m + ρ^(k−1)·(F1 − m), F1
// the predictor's one-step forecast. The predictor's own multi-step extrapolation is not
// used: its skill is only measured one step ahead, and at a gust it can pick a linear ramp
// that leaves the view for tens of pixels, which the loop never lets happen.
// The swing period seen last is kept: a swing does not stop when one fit of it is weak.
class SwingViewForecaster final : public ViewForecaster {
 public:
  // Fewer measured one-step errors than this: not trained.
  static constexpr int kMinErrorSamples = 10;
  static constexpr double kMinResonance = 0.8;  // [1] root modulus of a swing, per frame

  explicit SwingViewForecaster(int error_frames = 40);

  void Observe(const ShutterFrame& frame) override;
  bool trained() const override;
  cv::Point2d Forecast(int frames) const override;
  cv::Point2d error_rms() const override;
  std::optional<double> period_frames() const override;
  // [1] per axis: the measured rate ρ at which the residual reverts to its recent mean.
  cv::Point2d reversion() const;

 private:
  SwingPredictor x_;
  SwingPredictor y_;
  SwingPredictor pan_;
  SwingPredictor tilt_;
  int error_frames_;
  std::deque<cv::Point2d> errors_;            // [px] one-step errors, newest last
  std::optional<cv::Point2d> expected_next_;  // [px] forecast for the coming frame
  std::deque<cv::Point2d> offsets_;           // [px] recent trusted offsets, newest last
  // offsets_[i] follows offsets_[i − 1] by one frame (no untrusted frame between them)
  std::deque<bool> follows_;
  std::optional<double> period_;  // [frames] the swing period seen last
  bool previous_trusted_ = false;
};

// [frames] period of the AR(2) fit a_1, a_2 (coefficients a_1…a_p, c of a SwingPredictor)
// when its roots are complex with modulus ≥ `min_modulus`; nothing otherwise. `modulus`
// receives the roots' modulus.
std::optional<double> Ar2PeriodFrames(const std::vector<double>& coefficients, double min_modulus,
                                      double* modulus = nullptr);

}  // namespace kapfix
