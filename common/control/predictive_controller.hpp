#pragma once

#include <deque>
#include <string>

#include "common/control/command_rate_limiter.hpp"
#include "common/control/controller.hpp"
#include "common/control/deg_per_px_estimator.hpp"
#include "common/control/proportional_controller.hpp"
#include "common/control/swing_predictor.hpp"

namespace kapfix {

struct PredictiveOptions {
  // The swing model per axis. Its lead_frames must be the loop's delay: frames from the
  // capture of a frame to the first frame that shows the command sent for it, i.e. 1 + the
  // servo's latency in frames (SimulatedPlatform::Step).
  SwingPredictorOptions predictor;
  // [frames] the servo's latency jitter: a command takes effect lead_frames … lead_frames +
  // this after, so the forecast acted on is the mean over those leads weighted by how often
  // each is the one in effect (DelayShares), the aim that misses least on average. 0: a
  // fixed latency.
  int lead_jitter_frames = 0;
  // Below this match confidence a frame is treated as missing (the model coasts).
  double min_confidence = 0.0;
  // Online calibration: while the estimate of an axis's deg per px is trusted, the
  // calibration the controller acts on moves towards it every adapt_every_frames by at most
  // the factor adapt_max_step (bounded rate of change); before it was first trusted, towards
  // the frame's calibration hint (ControlInput) if there is one. false: the estimate is only
  // reported.
  bool adapt_calibration = true;
  int adapt_every_frames = 5;   // [frames]
  double adapt_max_step = 2.0;  // [1] > 1
  DegPerPxEstimatorOptions estimator;

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
// band holds an axis whose correction is smaller than the gains' one; the rate limit applies
// last; I and D are not used. A frame without a measurement is bridged by the forecast for a
// few frames, then the servos hold; while the lock is lost (ControlInput::return_to) they
// head for the return point the loop gives (the centre of the swing seen) instead.
class PredictiveController final : public Controller {
 public:
  // Throws std::invalid_argument for gains, calibration or options that are not IsValid.
  PredictiveController(ControllerGains gains, LensCalibration calibration,
                       PredictiveOptions options = {});

  ServoTargets Update(const ControlInput& input, const ServoTargets& current) override;
  void Reset() override;
  std::string name() const override { return "predictive"; }
  // A new stored calibration: the online estimate starts again from it. The swing models
  // are rebuilt from the recent frames in pixels of the new calibration.
  void SetCalibration(const LensCalibration& calibration) override;
  // Keeps the swing models, the online calibration and the hand-over state.
  void SetGains(const ControllerGains& gains) override;
  // Per axis: the online deg/px estimate, its relative σ, trust, and the forecast weight.
  std::optional<ControlEstimate> estimate() const override;
  // The calibration the controller acts on now (the stored one, moved by the online estimate).
  const LensCalibration& calibration() const { return calibration_; }

  // Whether each axis acted on its forecast (not the P fallback) at the last Update.
  bool predicting_pan() const { return predicting_pan_; }
  // [0, 1] share of the forecast in each axis's target (1 forecast, 0 plain P).
  double pan_forecast_weight() const { return pan_trust_.weight; }
  double tilt_forecast_weight() const { return tilt_trust_.weight; }
  bool predicting_tilt() const { return predicting_tilt_; }
  const SwingPredictor& pan_predictor() const { return pan_; }
  const SwingPredictor& tilt_predictor() const { return tilt_; }
  // The online estimates of each axis's deg per px (from the commands and the measured
  // response; see DegPerPxEstimator).
  const DegPerPxEstimator& pan_estimator() const { return pan_estimator_; }
  const DegPerPxEstimator& tilt_estimator() const { return tilt_estimator_; }

 private:
  ControllerGains gains_;
  LensCalibration calibration_;
  PredictiveOptions options_;
  // Plain P without the rate limit: the blend of it and the forecast is limited once, last.
  ProportionalController fallback_;
  CommandRateLimiter rate_limiter_;
  SwingPredictor pan_;
  SwingPredictor tilt_;
  DegPerPxEstimator pan_estimator_;
  DegPerPxEstimator tilt_estimator_;
  // Recent frames, per axis (angle [deg], displacement [px]; NaN displacement: missing), from
  // which the swing models are rebuilt when the calibration moves.
  struct Sample {
    double pan_deg, tilt_deg, dx_px, dy_px;
  };
  std::deque<Sample> recent_;
  int since_adapt_ = 0;   // [frames] since the calibration last moved (or was checked)
  bool adapted_ = false;  // the calibration moved since the stored one was given
  // [deg/px] the newest frame's calibration hints (ControlInput), 0: none
  double pan_hint_ = 0;
  double tilt_hint_ = 0;
  bool Adapt();  // true when the calibration moved (the swing models were rebuilt)
  void RebuildSwingModels();
  bool predicting_pan_ = false;
  bool predicting_tilt_ = false;
  double frame_period_s_ = 0;  // [s] shortest dt seen: one frame; 0 = none yet
  // Per axis: how far the forecast is trusted against P (1: forecast, 0: P), graded on the
  // residual the camera shows; see GradeForecast.
  struct AxisTrust {
    double weight = 1.0;
    double residual_sq = 0;  // [px²] EMA of the squared residual while the forecast leads
    int graded = 0;          // frames graded since the last hand-over
    int hold = 0;            // [frames] left before the forecast may come back
  };
  AxisTrust pan_trust_;
  AxisTrust tilt_trust_;

  // The steps of Update.
  void Remember(const ServoTargets& current, double dx_px, double dy_px);
  // Frames lost between two calls (dt of several frame periods) as missing samples.
  void CountLostFrames(double dt_s, const ServoTargets& current);
  // No measurement this frame: bridge with the forecast, then hold; or head for
  // input.return_to (a lost lock).
  ServoTargets Coast(const ControlInput& input, const ServoTargets& current);
  // [deg] the angle that cancels `predictor`'s forecast lead_frames ahead: an axis bridged
  // without a measurement (the predictor coasts, so it has a forecast).
  double CoastedDeg(const SwingPredictor& predictor, double deg_per_px) const;
  // Moves an axis's trust in its forecast against P by the residual the camera shows.
  void GradeForecast(const SwingPredictor& predictor, AxisTrust* trust, double measured_px);
  // One axis of this frame, as Update sees it.
  struct AxisFrame {
    bool measured = false;        // the frame measured this axis
    bool coasts = false;          // not measured, and the predictor bridges it
    double measured_px = 0;       // [px] the measurement (when measured)
    double current_deg = 0;       // [deg] the servo's angle the frame was seen through
    double deg_per_px = 0;        // [deg/px] the calibration acted on
    double proportional_deg = 0;  // [deg] P's target, the forecast's fallback
  };
  // The axis's target [deg]: aimed when measured (its forecast graded first), coasted on the
  // forecast when bridged, held otherwise.
  double SteerAxis(const SwingPredictor& predictor, AxisTrust* trust, const AxisFrame& frame,
                   bool* predicting);
  // The axis's target [deg]: the forecast and P's target blended by the trust.
  double AimAxis(const SwingPredictor& predictor, const AxisTrust& trust, double current_deg,
                 double deg_per_px, double fallback_deg, bool* predicting) const;
};

}  // namespace kapfix
