#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "agent/modes/agent_mode.hpp"
#include "common/control/controller.hpp"
#include "kapfix/v1/command.pb.h"

namespace kapfix::agent {

// What an agent restart resumes (issue 14): the operator's settings as the settings commands
// that changed them, the mode and slice, and the reference the fixation held.
struct ResumeRecord {
  // set_gains, set_search, set_camera, set_lens, set_video, set_photo:
  // applied in this order over the configuration, each range-checked as a station's command.
  std::vector<kapfix::v1::Command> settings;
  AgentMode mode = AgentMode::kIdle;
  int slice = 0;              // [1..slice_count] 0 = none
  cv::Mat reference_frame;    // BGR frame the fixation's reference was taken from; empty = none
  ServoTargets reference_at;  // [deg] the servo angles it was seen through
};

}  // namespace kapfix::agent
