#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/control/controller.hpp"
#include "common/control/predictive_controller.hpp"

namespace kapfix {

// "p" (ProportionalController), "pid" (PidController) or "predictive" (PredictiveController
// with `predictive`); nullptr and a reason for another name. Throws std::invalid_argument for
// gains, a calibration or options that are not IsValid.
std::unique_ptr<Controller> MakeController(std::string_view name, const ControllerGains& gains,
                                           const LensCalibration& calibration,
                                           const PredictiveOptions& predictive, std::string* error);
// The names MakeController accepts, the default ("predictive") last.
const std::vector<std::string>& ControllerNames();

}  // namespace kapfix
