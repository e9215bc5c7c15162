#include "common/control/proportional_controller.hpp"

#include <cmath>
#include <stdexcept>

namespace kapfix {
namespace {

double Correction(double displacement_px, double dead_band_px) {
  return std::abs(displacement_px) >= dead_band_px ? displacement_px : 0.0;
}

}  // namespace

ProportionalController::ProportionalController(ControllerGains gains, LensCalibration calibration)
    : gains_(gains) {
  std::string error;
  if (!gains_.IsValid(&error)) throw std::invalid_argument("ProportionalController: " + error);
  SetCalibration(calibration);
}

void ProportionalController::SetCalibration(const LensCalibration& calibration) {
  std::string error;
  if (!calibration.IsValid(&error)) throw std::invalid_argument("ProportionalController: " + error);
  calibration_ = calibration;
}

void ProportionalController::SetGains(const ControllerGains& gains) {
  std::string error;
  if (!gains.IsValid(&error)) throw std::invalid_argument("ProportionalController: " + error);
  gains_ = gains;
}

ServoTargets ProportionalController::Update(const ControlInput& input,
                                            const ServoTargets& current) {
  const cv::Point2d d = input.displacement_px;
  if (!input.found || !std::isfinite(d.x) || !std::isfinite(d.y)) return current;
  const ServoTargets target{current.pan_deg + gains_.p * Correction(d.x, gains_.dead_band_px) *
                                                  calibration_.pan_deg_per_px,
                            current.tilt_deg + gains_.p * Correction(d.y, gains_.dead_band_px) *
                                                   calibration_.tilt_deg_per_px};
  return ApplyRateLimit(target, current, gains_.rate_limit_deg_per_s, input.dt_s);
}

}  // namespace kapfix
