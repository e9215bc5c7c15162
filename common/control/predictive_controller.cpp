#include "common/control/predictive_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kapfix {
namespace {

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

  const auto axis = [this](const SwingPredictor& predictor, double current_deg, double deg_per_px,
                           double fallback_deg, bool* predicting) {
    const std::optional<double> ahead = predictor.Predict();
    if (!ahead) return fallback_deg;
    *predicting = true;
    const double correction_px = *ahead - current_deg / deg_per_px;
    if (std::abs(correction_px) < gains_.dead_band_px) return current_deg;
    return current_deg + gains_.p * correction_px * deg_per_px;
  };
  target.pan_deg = axis(pan_, current.pan_deg, calibration_.pan_deg_per_px, proportional.pan_deg,
                        &predicting_pan_);
  target.tilt_deg = axis(tilt_, current.tilt_deg, calibration_.tilt_deg_per_px,
                         proportional.tilt_deg, &predicting_tilt_);
  return ApplyRateLimit(target, current, gains_.rate_limit_deg_per_s, input.dt_s);
}

}  // namespace kapfix
