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
  return controller_->Update(input, belief_->Resolve(input, calibration_));
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
