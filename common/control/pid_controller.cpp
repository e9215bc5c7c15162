#include "common/control/pid_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace kapfix {

PidController::PidController(ControllerGains gains, LensCalibration calibration) : gains_(gains) {
  std::string error;
  if (!gains_.IsValid(&error)) throw std::invalid_argument("PidController: " + error);
  SetCalibration(calibration);
}

void PidController::SetCalibration(const LensCalibration& calibration) {
  std::string error;
  if (!calibration.IsValid(&error)) throw std::invalid_argument("PidController: " + error);
  calibration_ = calibration;
}

void PidController::SetGains(const ControllerGains& gains) {
  std::string error;
  if (!gains.IsValid(&error)) throw std::invalid_argument("PidController: " + error);
  // Bumpless: the integral term i · I stays what it was (within the new anti-windup limit).
  if (gains.i > 0 && gains_.i > 0) {
    integral_ *= gains_.i / gains.i;
    const double limit = gains.integral_limit_px / gains.i;
    integral_.x = std::clamp(integral_.x, -limit, limit);
    integral_.y = std::clamp(integral_.y, -limit, limit);
  }
  gains_ = gains;
}

void PidController::Reset() {
  integral_ = {0, 0};
  previous_ = {0, 0};
  has_previous_ = false;
  rate_limiter_.Reset();
}

ServoTargets PidController::Update(const ControlInput& input, const ServoTargets& current) {
  const cv::Point2d d = input.displacement_px;
  if (!input.found || (!std::isfinite(d.x) && !std::isfinite(d.y))) {
    has_previous_ = false;  // the next difference would span the gap
    return rate_limiter_.Unmeasured(gains_, input, current);
  }
  // An axis the frame did not measure (NaN) holds: no correction, its integral unchanged and
  // its last error kept for the next difference.
  const bool x = std::isfinite(d.x);
  const bool y = std::isfinite(d.y);
  const cv::Point2d e(x ? gains_.Correctable(d.x) : previous_.x,
                      y ? gains_.Correctable(d.y) : previous_.y);
  const bool timed = std::isfinite(input.dt_s) && input.dt_s > 0.0;
  cv::Point2d derivative(0, 0);
  if (timed) {
    integral_ += cv::Point2d(x ? e.x : 0.0, y ? e.y : 0.0) * input.dt_s;
    if (gains_.i > 0.0) {
      // Anti-windup: the integral may not ask for more than integral_limit_px on its own.
      const double limit = gains_.integral_limit_px / gains_.i;
      integral_.x = std::clamp(integral_.x, -limit, limit);
      integral_.y = std::clamp(integral_.y, -limit, limit);
    }
    if (has_previous_) derivative = (e - previous_) / input.dt_s;
  }
  previous_ = e;
  has_previous_ = true;
  cv::Point2d correction_px = gains_.p * e + gains_.i * integral_ + gains_.d * derivative;
  if (!x) correction_px.x = 0;
  if (!y) correction_px.y = 0;
  const ServoTargets target{current.pan_deg + correction_px.x * calibration_.pan_deg_per_px,
                            current.tilt_deg + correction_px.y * calibration_.tilt_deg_per_px};
  return rate_limiter_.Limit(gains_, target, current, input.dt_s);
}

}  // namespace kapfix
