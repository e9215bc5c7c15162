#pragma once

#include <memory>
#include <optional>

#include "agent/modes/calibration_run.hpp"
#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"

namespace kapfix::agent {

// Calibrate (SPEC §2.7): the servos are moved by known amounts around where they were and
// the view's displacement is read (CalibrationRun); at the end the lens profile's deg/px is
// fitted, applied to the settings the modes use and reported (ModeEvents::
// OnCalibrationReport, which stores it); then idle, the servos back where they started.
class CalibrateMode : public Mode {
 public:
  explicit CalibrateMode(ModeContext& context) : context_(context) {}

  AgentMode kind() const override { return AgentMode::kCalibrate; }
  // Throws std::invalid_argument when the lens's deg/px gives no usable moves.
  void Enter(const CapturedFrame& frame, const ServoTargets& current) override;
  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;

 private:
  // The fitted deg/px when the run gave a usable fit (applied to the context's settings).
  std::optional<LensCalibration> Fit(const std::string& lens, std::optional<AxisCalibration>* pan,
                                     std::optional<AxisCalibration>* tilt);

  ModeContext& context_;
  ServoTargets hold_;  // [deg] where the moves start from and the servos end
  std::shared_ptr<const SearchStrategy> strategy_;  // the one the run started with
  std::optional<CalibrationRun> run_;
  int progress_ = -1;  // moves_done last reported
};

}  // namespace kapfix::agent
