#pragma once

#include "common/control/command_rate_limiter.hpp"
#include "common/control/controller.hpp"

namespace kapfix {

// The thesis's plain proportional control through the calibration: per axis,
//   target = current + p · displacement · deg_per_px   when |displacement| ≥ dead band,
//   target = current                                   otherwise,
// then the rate limit. The I and D gains are ignored. Not found: the servos hold.
//
// Reacting only to what was measured, it trails the swing by the loop's delay: one frame of
// measurement plus the servo's latency (SPEC §3).
class ProportionalController final : public Controller {
 public:
  // Throws std::invalid_argument for gains or a calibration that are not IsValid.
  ProportionalController(ControllerGains gains, LensCalibration calibration);

  ServoTargets Update(const ControlInput& input, const ServoTargets& current) override;
  void Reset() override { rate_limiter_.Reset(); }
  std::string name() const override { return "p"; }
  void SetCalibration(const LensCalibration& calibration) override;
  void SetGains(const ControllerGains& gains) override;

 private:
  ControllerGains gains_;
  LensCalibration calibration_;
  CommandRateLimiter rate_limiter_;
};

}  // namespace kapfix
