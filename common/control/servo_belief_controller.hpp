#pragma once

#include <memory>
#include <string>

#include "common/control/controller.hpp"
#include "common/control/servo_belief.hpp"

namespace kapfix {

// Hands the controller it wraps the angles a frame was seen through as the servo belief
// resolves them from that frame's measurement (ServoBelief::Resolve), instead of the
// `current` its caller could give before the frame was measured (the belief's expectation,
// ServoBelief::Expose). The caller tells the belief which frame is processed (Expose) and what
// was sent (Sent); this class only sits where the measurement and the controller meet.
// The belief is given the stored calibration (SetCalibration), not an online estimate the
// wrapped controller may act on, and finds the scale of it that keeps its views smooth
// itself (ServoBelief::scale): a calibration ×1.3 off roughened them enough to pick the wrong
// command of two. That scale of the stored calibration goes to the controller as the frame's
// calibration hint (ControlInput), which a predictive controller acts on until its own
// estimate is trusted. The controller aims the servos' outputs (the camera); what is returned
// is the command that brings them there through the servos' play (ServoBelief::ShaftCommand).
class ServoBeliefController final : public Controller {
 public:
  // Throws std::invalid_argument for a null controller or belief, or a calibration that is
  // not IsValid.
  ServoBeliefController(std::unique_ptr<Controller> controller, std::shared_ptr<ServoBelief> belief,
                        LensCalibration calibration);

  ServoTargets Update(const ControlInput& input, const ServoTargets& current) override;
  void Reset() override;
  std::string name() const override { return controller_->name(); }
  void SetCalibration(const LensCalibration& calibration) override;
  void SetGains(const ControllerGains& gains) override { controller_->SetGains(gains); }
  std::optional<ControlEstimate> estimate() const override { return controller_->estimate(); }

  const Controller& controller() const { return *controller_; }

 private:
  std::unique_ptr<Controller> controller_;
  std::shared_ptr<ServoBelief> belief_;
  LensCalibration calibration_;
};

}  // namespace kapfix
