#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>

#include "agent/capture/frame_source.hpp"
#include "agent/modes/agent_mode.hpp"
#include "common/fixation/fixation_loop.hpp"

namespace kapfix::agent {

// What the control thread made of one frame.
struct FrameOutcome {
  FixationLoop::Step step;  // the match (not found when nothing was measured) and the targets
  AgentMode mode = AgentMode::kIdle;
  int slice = 0;        // [1..slice_count] slice in use; 0 = none
  int slice_count = 0;  // [count] bands of the frame
  cv::Rect patch;       // [px] reference patch in the reference frame; empty = none
  // Fixate: the index of the frame whose view is held; none in the other modes.
  std::optional<std::uint64_t> reference_frame;
  cv::Point2d reference_seen_at{0, 0};  // [px] HeldView::seen_at of that frame
};

// What the control thread runs on each frame: ModeRunner in the agent, anything in tests.
class FrameProcessor {
 public:
  virtual ~FrameProcessor() = default;
  // `current`: the servo angles the frame was seen through; `dt_s`: time since the previous
  // frame [s].
  virtual FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                               double dt_s) = 0;
};

}  // namespace kapfix::agent
