#include "common/control/predictive_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kapfix {
namespace {

// The hand-over between forecast and P (see Update).
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

}  // namespace

bool PredictiveOptions::IsValid(std::string* error) const {
  if (!predictor.IsValid(error)) return false;
  if (!(min_confidence >= 0.0 && min_confidence <= 1.0)) {
    if (error) *error = "min confidence must be in [0, 1], got " + std::to_string(min_confidence);
    return false;
  }
  return true;
}

PredictiveController::PredictiveController(ControllerGains gains, LensCalibration calibration,
                                           PredictiveOptions options)
    : gains_(gains),
      calibration_(calibration),
      options_(Validated(options)),
      fallback_(gains, calibration),  // validates gains and calibration
      pan_(options_.predictor),
      tilt_(options_.predictor) {}

void PredictiveController::Reset() {
  pan_.Clear();
  tilt_.Clear();
  fallback_.Reset();
  pan_trust_ = tilt_trust_ = {};
  predicting_pan_ = predicting_tilt_ = false;
}

void PredictiveController::SetCalibration(const LensCalibration& calibration) {
  fallback_.SetCalibration(calibration);  // validates
  calibration_ = calibration;
  Reset();
}

ServoTargets PredictiveController::Update(const ControlInput& input, const ServoTargets& current) {
  const cv::Point2d d = input.displacement_px;
  const bool measured = input.found && std::isfinite(d.x) && std::isfinite(d.y) &&
                        input.confidence >= options_.min_confidence;
  ServoTargets target = current;
  predicting_pan_ = predicting_tilt_ = false;
  // Frames the camera lost show as a dt of several frame periods (the shortest dt seen):
  // the swing models get them as missing samples, so their one-sample-per-frame clock holds.
  if (std::isfinite(input.dt_s) && input.dt_s > 0) {
    if (frame_period_s_ <= 0 || input.dt_s < frame_period_s_) frame_period_s_ = input.dt_s;
    const int lost = static_cast<int>(std::lround(input.dt_s / frame_period_s_)) - 1;
    for (int k = 0; k < std::min(lost, options_.predictor.max_coast_frames + 1); ++k) {
      pan_.AddMissing();
      tilt_.AddMissing();
    }
  }
  if (!measured) {
    // Bridge a short gap with the forecast; hold once the models give up.
    const bool pan_coasts = pan_.AddMissing();
    const bool tilt_coasts = tilt_.AddMissing();
    if (pan_coasts) {
      target.pan_deg = *pan_.Forecast(options_.predictor.lead_frames) * calibration_.pan_deg_per_px;
      predicting_pan_ = true;
    }
    if (tilt_coasts) {
      target.tilt_deg =
          *tilt_.Forecast(options_.predictor.lead_frames) * calibration_.tilt_deg_per_px;
      predicting_tilt_ = true;
    }
    return ApplyRateLimit(target, current, gains_.rate_limit_deg_per_s, input.dt_s);
  }

  // The uncorrected view [px]: what the servo compensated plus what was still left.
  pan_.Add(current.pan_deg / calibration_.pan_deg_per_px + d.x);
  tilt_.Add(current.tilt_deg / calibration_.tilt_deg_per_px + d.y);
  const ServoTargets proportional = fallback_.Update(input, current);

  const auto axis = [this](const SwingPredictor& predictor, AxisTrust* trust, double measured_px,
                           double current_deg, double deg_per_px, double fallback_deg,
                           bool* predicting) {
    // The forecast it acted on is graded by what the camera shows lead frames later: the
    // residual displacement is that forecast's error. P's would be persistence's error
    // (what P acts on). While the residual grows beyond persistence's, the forecast hands
    // over to P smoothly; it comes back only after a hold-off and while its own forecasts
    // of the swing are clearly better than persistence.
    const double persistence = predictor.skill_rms(SwingPredictor::Forecaster::kPersistence);
    if (trust->weight > 0.5) {
      // Inside the dead band both controllers leave the residual alone on purpose.
      const double excess = std::max(0.0, std::abs(measured_px) - gains_.dead_band_px);
      trust->residual_sq += kTrustRate * (excess * excess - trust->residual_sq);
      ++trust->graded;
    }
    const bool graded = trust->graded >= kTrustMinGraded && std::isfinite(persistence);
    if (graded && trust->weight > 0 &&
        std::sqrt(trust->residual_sq) > kHandOverRatio * persistence) {
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
    const std::optional<double> ahead = predictor.Predict();
    if (!ahead || trust->weight == 0.0) return fallback_deg;
    *predicting = true;
    const double correction_px = *ahead - current_deg / deg_per_px;
    const double forecast_deg = std::abs(correction_px) < gains_.dead_band_px
                                    ? current_deg
                                    : current_deg + gains_.p * correction_px * deg_per_px;
    return trust->weight * forecast_deg + (1.0 - trust->weight) * fallback_deg;
  };
  target.pan_deg = axis(pan_, &pan_trust_, d.x, current.pan_deg, calibration_.pan_deg_per_px,
                        proportional.pan_deg, &predicting_pan_);
  target.tilt_deg = axis(tilt_, &tilt_trust_, d.y, current.tilt_deg, calibration_.tilt_deg_per_px,
                         proportional.tilt_deg, &predicting_tilt_);
  return ApplyRateLimit(target, current, gains_.rate_limit_deg_per_s, input.dt_s);
}

}  // namespace kapfix
