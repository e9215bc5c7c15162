#pragma once

#include <opencv2/core.hpp>

#include "common/control/command_rate_limiter.hpp"
#include "common/control/controller.hpp"

namespace kapfix {

// PID on the measured displacement, per axis, through the calibration:
//   e = displacement, or 0 inside the dead band
//   I += e · dt,  clamped so that |i · I| ≤ integral_limit_px (anti-windup)
//   target = current + deg_per_px · (p · e + i · I + d · (e − e_previous) / dt)
// then the rate limit. Since the servo holds the angle it is sent, the loop already
// integrates once: P alone removes a constant offset, and I works against the steady lag of
// a ramp (a slow drift). The derivative is skipped on the first frame and after a frame
// without a measurement. Not found: the servos hold, I is kept.
class PidController final : public Controller {
 public:
  // Throws std::invalid_argument for gains or a calibration that are not IsValid.
  PidController(ControllerGains gains, LensCalibration calibration);

  ServoTargets Update(const ControlInput& input, const ServoTargets& current) override;
  void Reset() override;
  std::string name() const override { return "pid"; }
  void SetCalibration(const LensCalibration& calibration) override;
  // Keeps the integral term's contribution i · I across a change of i (I is rescaled), so the
  // target does not jump.
  void SetGains(const ControllerGains& gains) override;

  // [px·s] the integral of the displacement so far.
  cv::Point2d integral() const { return integral_; }

 private:
  ControllerGains gains_;
  LensCalibration calibration_;
  cv::Point2d integral_{0, 0};
  cv::Point2d previous_{0, 0};
  bool has_previous_ = false;
  CommandRateLimiter rate_limiter_;
};

}  // namespace kapfix
