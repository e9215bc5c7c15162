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

 private:
  SwingPredictor x_;
  SwingPredictor y_;
  SwingPredictor pan_;
  SwingPredictor tilt_;
  int error_frames_;
  std::deque<cv::Point2d> errors_;            // [px] one-step errors, newest last
  std::optional<cv::Point2d> expected_next_;  // [px] forecast for the coming frame
};

// [frames] period of the AR(2) fit a_1, a_2 (coefficients a_1…a_p, c of a SwingPredictor)
// when its roots are complex with modulus ≥ `min_modulus`; nothing otherwise. `modulus`
// receives the roots' modulus.
std::optional<double> Ar2PeriodFrames(const std::vector<double>& coefficients, double min_modulus,
                                      double* modulus = nullptr);

}  // namespace kapfix
