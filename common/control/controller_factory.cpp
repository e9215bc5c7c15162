#include "common/control/controller_factory.hpp"

#include "common/control/pid_controller.hpp"
#include "common/control/proportional_controller.hpp"

namespace kapfix {

const std::vector<std::string>& ControllerNames() {
  static const std::vector<std::string> names = {"p", "pid", "predictive"};
  return names;
}

std::unique_ptr<Controller> MakeController(std::string_view name, const ControllerGains& gains,
                                           const LensCalibration& calibration,
                                           const PredictiveOptions& predictive,
                                           std::string* error) {
  if (name == "p") return std::make_unique<ProportionalController>(gains, calibration);
  if (name == "pid") return std::make_unique<PidController>(gains, calibration);
  if (name == "predictive") {
    return std::make_unique<PredictiveController>(gains, calibration, predictive);
  }
  if (error) *error = "unknown controller '" + std::string(name) + "' (p, pid or predictive)";
  return nullptr;
}

}  // namespace kapfix
