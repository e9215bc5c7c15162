#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "agent/modes/agent_mode.hpp"
#include "common/control/controller.hpp"
#include "common/control/lens_calibration.hpp"
#include "kapfix/v1/calibration.pb.h"
#include "kapfix/v1/slices.pb.h"

namespace kapfix::agent {

// Where ModeRunner's results go: the agent's state and the link (CommandExecutor), or a
// recorder in tests. Called on the control thread: implementations only copy and queue.
class ModeEvents {
 public:
  virtual ~ModeEvents() = default;
  virtual void OnModeChanged(AgentMode mode, int slice) = 0;
  // Progress while SSP runs, and once more with finished = true.
  virtual void OnSliceReport(const kapfix::v1::SliceReport& report) = 0;
  virtual void OnPssReport(const kapfix::v1::PssReport& report) = 0;
  // Progress while calibrating, and once more with finished = true. `applied`: the deg/px the
  // runner now uses for the lens profile, when the fit was usable.
  virtual void OnCalibrationReport(const kapfix::v1::CalibrationReport& report,
                                   const std::optional<LensCalibration>& applied) = 0;
  // A free swing was recorded to `path` (or failed: `error` says why).
  virtual void OnFreeSwingRecorded(const std::string& path, const std::string& error) = 0;
  // Fixate took a new reference from `frame_bgr` (never written again: share it, do not
  // copy), seen through the servo angles `servos` (issue 14: what a restart resumes).
  virtual void OnReferenceTaken(const cv::Mat& /*frame_bgr*/, const ServoTargets& /*servos*/) {}
  // A resume (ModeRunner::RequestResume) ended: the stored view was found and the agent
  // fixates it (`resumed`), or it was not and the agent is idle.
  virtual void OnResumeEnded(bool /*resumed*/) {}
};

}  // namespace kapfix::agent
