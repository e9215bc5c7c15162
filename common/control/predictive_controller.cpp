#include "common/control/predictive_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/control/servo_belief.hpp"

namespace kapfix {
namespace {

// The hand-over between forecast and P (see GradeForecast).
constexpr double kTrustRate = 0.05;        // [1/frame] EMA rate of the squared residual
constexpr int kTrustMinGraded = 20;        // [frames] graded before it may hand over
constexpr double kHandOverRatio = 1.1;     // residual RMS beyond this × persistence's: worse
constexpr double kHandOverStep = 0.1;      // [1/frame] how fast the weight moves to P
constexpr int kReturnHoldFrames = 100;     // [frames] P keeps the axis at least this long
constexpr double kReturnSkillRatio = 0.5;  // the model must forecast this much better to return
constexpr double kReturnStep = 0.02;       // [1/frame] how fast the weight moves back

const PredictiveOptions& Validated(const PredictiveOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("PredictiveController: " + error);
  return options;
}

const ControllerGains& Validated(const ControllerGains& gains) {
  std::string error;
  if (!gains.IsValid(&error)) throw std::invalid_argument("PredictiveController: " + error);
  return gains;
}

}  // namespace

bool PredictiveOptions::IsValid(std::string* error) const {
  if (!predictor.IsValid(error)) return false;
  if (lead_jitter_frames < 0 || lead_jitter_frames > 100) {
    if (error)
      *error = "lead jitter must be 0…100 frames, got " + std::to_string(lead_jitter_frames);
    return false;
  }
  if (!(min_confidence >= 0.0 && min_confidence <= 1.0)) {
    if (error) *error = "min confidence must be in [0, 1], got " + std::to_string(min_confidence);
    return false;
  }
  if (adapt_every_frames < 1 || adapt_every_frames > 100000 || !(adapt_max_step > 1.0) ||
      !(adapt_max_step <= 2.0)) {
    if (error) {
      *error = "calibration adaptation needs every 1…100000 frames and a step in (1, 2], got " +
               std::to_string(adapt_every_frames) + " and " + std::to_string(adapt_max_step);
    }
    return false;
  }
  return estimator.IsValid(error);
}

PredictiveController::PredictiveController(ControllerGains gains, LensCalibration calibration,
                                           PredictiveOptions options)
    : gains_(Validated(gains)),
      calibration_(calibration),
      options_(Validated(options)),
      fallback_(gains.WithoutRateLimit(), calibration),  // validates the calibration
      pan_(options_.predictor),
      tilt_(options_.predictor),
      pan_estimator_(calibration.pan_deg_per_px, options_.estimator),
      tilt_estimator_(calibration.tilt_deg_per_px, options_.estimator) {}

void PredictiveController::Reset() {
  pan_.Clear();
  tilt_.Clear();
  fallback_.Reset();
  rate_limiter_.Reset();
  pan_trust_ = tilt_trust_ = {};
  predicting_pan_ = predicting_tilt_ = false;
  recent_.clear();
  // The lens has not changed: the calibration estimate stays, its lags restart.
  pan_estimator_.AddMissing();
  tilt_estimator_.AddMissing();
}

void PredictiveController::RebuildSwingModels() {
  pan_.Clear();
  tilt_.Clear();
  // A missing displacement (NaN) is a missing sample of that axis alone.
  for (const Sample& s : recent_) {
    pan_.Add(s.pan_deg / calibration_.pan_deg_per_px + s.dx_px);
    tilt_.Add(s.tilt_deg / calibration_.tilt_deg_per_px + s.dy_px);
  }
}

bool PredictiveController::Adapt() {
  // Until the calibration first moves, every frame is checked: on lock-on a wrong
  // calibration costs the most, and the estimate's first trusted fit should act at once.
  if (!options_.adapt_calibration || (++since_adapt_ < options_.adapt_every_frames && adapted_)) {
    return false;
  }
  since_adapt_ = 0;
  const auto toward = [this](double now, const DegPerPxEstimator& estimator, double hint) {
    double target = now;
    if (estimator.trusted()) {
      target = estimator.estimate_deg_per_px();
    } else if (!estimator.ever_trusted() && std::isfinite(hint) && hint / now > 0) {
      // Lock-on under latency jitter: the estimate needs the angles each frame was seen
      // through, which the servo belief picks right only once its views are smooth — so the
      // scale that makes them smooth is the better calibration until the estimate is trusted.
      // Flying the stored one ×1.3 off rang the pull-in and kept the estimate from ever being
      // trusted (realistic world without drops, seed 3: 14 px RMS on five photos).
      target = hint;
    }
    const double step = options_.adapt_max_step;
    const double ratio = std::clamp(target / now, 1.0 / step, step);
    // Within 1 % the move is not worth rebuilding the swing models for.
    return std::abs(ratio - 1.0) < 0.01 ? now : now * ratio;
  };
  const LensCalibration next{toward(calibration_.pan_deg_per_px, pan_estimator_, pan_hint_),
                             toward(calibration_.tilt_deg_per_px, tilt_estimator_, tilt_hint_)};
  if (next.pan_deg_per_px == calibration_.pan_deg_per_px &&
      next.tilt_deg_per_px == calibration_.tilt_deg_per_px) {
    return false;
  }
  calibration_ = next;
  adapted_ = true;
  fallback_.SetCalibration(calibration_);
  RebuildSwingModels();
  // The residual that handed an axis over to P was (partly) the old calibration's: grade the
  // forecast afresh, and let it come back as soon as it forecasts the swing well.
  for (AxisTrust* trust : {&pan_trust_, &tilt_trust_}) {
    trust->hold = 0;
    trust->residual_sq = 0;
    trust->graded = 0;
  }
  return true;
}

std::optional<ControlEstimate> PredictiveController::estimate() const {
  const auto axis = [](const DegPerPxEstimator& estimator, const AxisTrust& trust) {
    return ControlEstimate::Axis{estimator.estimate_deg_per_px(), estimator.relative_sigma(),
                                 estimator.trusted(), trust.weight};
  };
  return ControlEstimate{axis(pan_estimator_, pan_trust_), axis(tilt_estimator_, tilt_trust_)};
}

void PredictiveController::SetGains(const ControllerGains& gains) {
  fallback_.SetGains(Validated(gains).WithoutRateLimit());
  gains_ = gains;
}

void PredictiveController::SetCalibration(const LensCalibration& calibration) {
  fallback_.SetCalibration(calibration);  // validates
  calibration_ = calibration;
  pan_estimator_.Restart(calibration.pan_deg_per_px);
  tilt_estimator_.Restart(calibration.tilt_deg_per_px);
  since_adapt_ = 0;
  adapted_ = false;
  RebuildSwingModels();
}

void PredictiveController::Remember(const ServoTargets& current, double dx_px, double dy_px) {
  recent_.push_back({current.pan_deg, current.tilt_deg, dx_px, dy_px});
  while (static_cast<int>(recent_.size()) > options_.predictor.window_frames) {
    recent_.pop_front();
  }
}

void PredictiveController::CountLostFrames(double dt_s, const ServoTargets& current) {
  // Frames the camera lost show as a dt of several frame periods (the shortest dt seen):
  // the swing models get them as missing samples, so their one-sample-per-frame clock holds.
  if (!std::isfinite(dt_s) || dt_s <= 0) return;
  if (frame_period_s_ <= 0 || dt_s < frame_period_s_) frame_period_s_ = dt_s;
  const int lost = static_cast<int>(std::lround(dt_s / frame_period_s_)) - 1;
  for (int k = 0; k < std::min(lost, options_.predictor.max_coast_frames + 1); ++k) {
    pan_.AddMissing();
    tilt_.AddMissing();
    Remember(current, std::numeric_limits<double>::quiet_NaN(),
             std::numeric_limits<double>::quiet_NaN());
  }
  if (lost > 0) {
    pan_estimator_.AddMissing();
    tilt_estimator_.AddMissing();
  }
}

ServoTargets PredictiveController::Coast(const ControlInput& input, const ServoTargets& current) {
  pan_estimator_.AddMissing();
  tilt_estimator_.AddMissing();
  Remember(current, std::numeric_limits<double>::quiet_NaN(),
           std::numeric_limits<double>::quiet_NaN());
  const bool pan_coasts = pan_.AddMissing();
  const bool tilt_coasts = tilt_.AddMissing();
  // A lost lock: the frames before the loss may have been wrong matches, so the forecast
  // built on them is no better a guide than where the reference was.
  if (input.return_to) return rate_limiter_.Unmeasured(gains_, input, current);
  // Bridge a short gap with the forecast; hold once the models give up.
  ServoTargets target = current;
  if (pan_coasts) {
    target.pan_deg = CoastedDeg(pan_, calibration_.pan_deg_per_px);
    predicting_pan_ = true;
  }
  if (tilt_coasts) {
    target.tilt_deg = CoastedDeg(tilt_, calibration_.tilt_deg_per_px);
    predicting_tilt_ = true;
  }
  return rate_limiter_.Limit(gains_, target, current, input.dt_s);
}

double PredictiveController::CoastedDeg(const SwingPredictor& predictor, double deg_per_px) const {
  return *predictor.Forecast(options_.predictor.lead_frames) * deg_per_px;
}

void PredictiveController::GradeForecast(const SwingPredictor& predictor, AxisTrust* trust,
                                         double measured_px) {
  // The forecast it acted on is graded by what the camera shows lead frames later: the
  // residual displacement is that forecast's error. P's would be persistence's error
  // (what P acts on). While the residual grows beyond persistence's, the forecast hands
  // over to P smoothly; it comes back only after a hold-off and while its own forecasts
  // of the swing are clearly better than persistence.
  const double persistence = predictor.skill_rms(SwingPredictor::Forecaster::kPersistence);
  if (trust->weight > 0.5) {
    // Inside the dead band both controllers leave the residual alone on purpose.
    const double excess = gains_.BeyondDeadBand(measured_px);
    trust->residual_sq += kTrustRate * (excess * excess - trust->residual_sq);
    ++trust->graded;
  }
  const bool graded = trust->graded >= kTrustMinGraded && std::isfinite(persistence);
  if (graded && trust->weight > 0 && std::sqrt(trust->residual_sq) > kHandOverRatio * persistence) {
    trust->weight = std::max(0.0, trust->weight - kHandOverStep);
    if (trust->weight == 0.0) {
      trust->hold = kReturnHoldFrames;
      trust->residual_sq = 0;
      trust->graded = 0;
    }
  } else if (trust->hold > 0) {
    --trust->hold;
  } else if (trust->weight < 1.0) {
    const double model = predictor.skill_rms(SwingPredictor::Forecaster::kModel);
    if (!std::isfinite(model) || model < kReturnSkillRatio * persistence) {
      trust->weight = std::min(1.0, trust->weight + kReturnStep);
    }
  }
}

double PredictiveController::AimAxis(const SwingPredictor& predictor, const AxisTrust& trust,
                                     double current_deg, double deg_per_px, double fallback_deg,
                                     bool* predicting) const {
  std::optional<double> ahead = predictor.Predict();
  if (!ahead || trust.weight == 0.0) return fallback_deg;
  if (options_.lead_jitter_frames > 0) {
    const std::vector<double> shares = DelayShares(options_.lead_jitter_frames);
    *ahead *= shares[0];
    for (int k = 1; k <= options_.lead_jitter_frames; ++k) {
      *ahead += shares[k] * *predictor.Forecast(options_.predictor.lead_frames + k);
    }
  }
  *predicting = true;
  const double correction_px = *ahead - current_deg / deg_per_px;
  const double forecast_deg =
      current_deg + gains_.p * gains_.Correctable(correction_px) * deg_per_px;
  return trust.weight * forecast_deg + (1.0 - trust.weight) * fallback_deg;
}

ServoTargets PredictiveController::Update(const ControlInput& input, const ServoTargets& current) {
  const cv::Point2d d = input.displacement_px;
  const bool usable = input.found && input.confidence >= options_.min_confidence;
  // An axis the frame did not measure (NaN: the match was not sure along it) coasts on its
  // forecast while the other is steered by its measurement.
  const bool pan_measured = usable && std::isfinite(d.x);
  const bool tilt_measured = usable && std::isfinite(d.y);
  predicting_pan_ = predicting_tilt_ = false;
  CountLostFrames(input.dt_s, current);
  if (!pan_measured && !tilt_measured) return Coast(input, current);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double dx = pan_measured ? d.x : nan;
  const double dy = tilt_measured ? d.y : nan;

  pan_hint_ = input.pan_deg_per_px_hint;
  tilt_hint_ = input.tilt_deg_per_px_hint;
  pan_estimator_.Add(current.pan_deg, dx);
  tilt_estimator_.Add(current.tilt_deg, dy);
  Remember(current, dx, dy);
  const bool rebuilt = Adapt();  // before the models take this frame: a rebuild includes it
  // The uncorrected view [px]: what the servo compensated plus what was still left (a
  // rebuild in Adapt already added it); NaN is a missing sample.
  bool pan_coasts = false;
  bool tilt_coasts = false;
  if (!rebuilt) {
    if (pan_measured) {
      pan_.Add(current.pan_deg / calibration_.pan_deg_per_px + dx);
    } else {
      pan_coasts = pan_.AddMissing();
    }
    if (tilt_measured) {
      tilt_.Add(current.tilt_deg / calibration_.tilt_deg_per_px + dy);
    } else {
      tilt_coasts = tilt_.AddMissing();
    }
  } else {
    pan_coasts = !pan_measured && pan_.samples() > 0;
    tilt_coasts = !tilt_measured && tilt_.samples() > 0;
  }
  ControlInput measured = input;
  measured.displacement_px = {dx, dy};
  const ServoTargets proportional = fallback_.Update(measured, current);

  ServoTargets target;
  target.pan_deg = SteerAxis(pan_, &pan_trust_,
                             {pan_measured, pan_coasts, dx, current.pan_deg,
                              calibration_.pan_deg_per_px, proportional.pan_deg},
                             &predicting_pan_);
  target.tilt_deg = SteerAxis(tilt_, &tilt_trust_,
                              {tilt_measured, tilt_coasts, dy, current.tilt_deg,
                               calibration_.tilt_deg_per_px, proportional.tilt_deg},
                              &predicting_tilt_);
  return rate_limiter_.Limit(gains_, target, current, input.dt_s);
}

double PredictiveController::SteerAxis(const SwingPredictor& predictor, AxisTrust* trust,
                                       const AxisFrame& frame, bool* predicting) {
  if (frame.measured) {
    GradeForecast(predictor, trust, frame.measured_px);
    return AimAxis(predictor, *trust, frame.current_deg, frame.deg_per_px, frame.proportional_deg,
                   predicting);
  }
  if (frame.coasts) {
    *predicting = true;
    return CoastedDeg(predictor, frame.deg_per_px);
  }
  return frame.current_deg;
}

}  // namespace kapfix
