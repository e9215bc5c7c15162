#pragma once

#include <string>

#include "common/control/controller.hpp"
#include "common/control/proportional_controller.hpp"
#include "common/control/swing_predictor.hpp"

namespace kapfix {

struct PredictiveOptions {
  // The swing model per axis. Its lead_frames must be the loop's delay: frames from the
  // capture of a frame to the first frame that shows the command sent for it, i.e. 1 + the
  // servo's latency in frames (SimulatedPlatform::Step).
  SwingPredictorOptions predictor;
  // Below this match confidence a frame is treated as missing (the model coasts).
  double min_confidence = 0.0;

  bool IsValid(std::string* error) const;
};

// The default controller (SPEC §3): predicts the swing and feeds it forward.
//
// Per axis it reconstructs where the uncorrected view was at the frame just measured, in
// pixels: u = current / deg_per_px + displacement — the displacement the servo was already
// compensating plus what was left — which is the platform's own swing, free of the loop's
// feedback. A SwingPredictor forecasts u lead_frames ahead, to the frame the command will
// act on, and the target moves the servo that share p of the way to it:
//   target = current + p · (û(t + lead) − current / deg_per_px) · deg_per_px,
// which at p = 1 is û(t + lead) · deg_per_px, the angle that will hold that frame. While
// persistence forecasts best (the first frame or two, after a lost lock, a motion that is
// not a swing) the axis falls back to ProportionalController with the same gains, which acts
// on exactly that forecast; SwingPredictor says how the forecasters are chosen. The dead
// band holds an axis whose correction is smaller than dead_band_px; the rate limit applies
// last; I and D are not used. A frame without a measurement is bridged by the forecast for a
// few frames, then the servos hold.
class PredictiveController final : public Controller {
 public:
  // Throws std::invalid_argument for gains, calibration or options that are not IsValid.
  PredictiveController(ControllerGains gains, LensCalibration calibration,
                       PredictiveOptions options = {});

  ServoTargets Update(const ControlInput& input, const ServoTargets& current) override;
  void Reset() override;
  std::string name() const override { return "predictive"; }
  // Also forgets the swing models: they are kept in pixels of the old calibration.
  void SetCalibration(const LensCalibration& calibration) override;

  // Whether each axis acted on its forecast (not the P fallback) at the last Update.
  bool predicting_pan() const { return predicting_pan_; }
  // [0, 1] share of the forecast in each axis's target (1 forecast, 0 plain P).
  double pan_forecast_weight() const { return pan_trust_.weight; }
  double tilt_forecast_weight() const { return tilt_trust_.weight; }
  bool predicting_tilt() const { return predicting_tilt_; }
  const SwingPredictor& pan_predictor() const { return pan_; }
  const SwingPredictor& tilt_predictor() const { return tilt_; }

 private:
  ControllerGains gains_;
  LensCalibration calibration_;
  PredictiveOptions options_;
  ProportionalController fallback_;
  SwingPredictor pan_;
  SwingPredictor tilt_;
  bool predicting_pan_ = false;
  bool predicting_tilt_ = false;
  double frame_period_s_ = 0;  // [s] shortest dt seen: one frame; 0 = none yet
  // Per axis: how far the forecast is trusted against P (1: forecast, 0: P), graded on the
  // residual the camera shows; see Update.
  struct AxisTrust {
    double weight = 1.0;
    double residual_sq = 0;  // [px²] EMA of the squared residual while the forecast leads
    int graded = 0;          // frames graded since the last hand-over
    int hold = 0;            // [frames] left before the forecast may come back
  };
  AxisTrust pan_trust_;
  AxisTrust tilt_trust_;
};

}  // namespace kapfix
