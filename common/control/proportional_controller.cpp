#include "common/control/proportional_controller.hpp"

#include <cmath>
#include <stdexcept>

namespace kapfix {

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
  if (!input.found || (!std::isfinite(d.x) && !std::isfinite(d.y))) {
    return rate_limiter_.Unmeasured(gains_, input, current);
  }
  // An axis the frame did not measure (NaN) holds.
  const auto correction = [this](double px) {
    return std::isfinite(px) ? gains_.p * gains_.Correctable(px) : 0.0;
  };
  const ServoTargets target{current.pan_deg + correction(d.x) * calibration_.pan_deg_per_px,
                            current.tilt_deg + correction(d.y) * calibration_.tilt_deg_per_px};
  return rate_limiter_.Limit(gains_, target, current, input.dt_s);
}

}  // namespace kapfix
