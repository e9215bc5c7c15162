#include "common/control/servo_belief_controller.hpp"

#include <stdexcept>

namespace kapfix {

ServoBeliefController::ServoBeliefController(std::unique_ptr<Controller> controller,
                                             std::shared_ptr<ServoBelief> belief,
                                             LensCalibration calibration)
    : controller_(std::move(controller)), belief_(std::move(belief)), calibration_(calibration) {
  if (!controller_ || !belief_) {
    throw std::invalid_argument("ServoBeliefController: needs a controller and a servo belief");
  }
  std::string error;
  if (!calibration_.IsValid(&error)) throw std::invalid_argument("ServoBeliefController: " + error);
}

ServoTargets ServoBeliefController::Update(const ControlInput& input,
                                           const ServoTargets& /*current*/) {
  const ServoTargets seen = belief_->Resolve(input, calibration_);
  ControlInput hinted = input;
  const LensCalibration agreed = belief_->Scaled(calibration_);
  hinted.pan_deg_per_px_hint = agreed.pan_deg_per_px;
  hinted.tilt_deg_per_px_hint = agreed.tilt_deg_per_px;
  return belief_->ShaftCommand(controller_->Update(hinted, seen));
}

void ServoBeliefController::Reset() {
  belief_->ForgetViews();
  controller_->Reset();
}

void ServoBeliefController::SetCalibration(const LensCalibration& calibration) {
  controller_->SetCalibration(calibration);  // validates
  calibration_ = calibration;
}

}  // namespace kapfix
