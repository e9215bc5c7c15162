#pragma once

#include <opencv2/core.hpp>

#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"

namespace kapfix::agent {

// Coming back fixating the view an earlier run held (issue 14), before any other mode: the
// servos hold while the stored patch is searched over the whole frame. Found with enough
// confidence, it ends handing the view to fixate (from where it was found); not found within
// kResumeFrames, it ends idle. Reported as idle while it searches.
class ResumeMode : public Mode {
 public:
  // [frames] the stored view is searched for this long (about a second, so a swing that
  // carried it out of the frame brings it back) before the agent gives up and stays idle.
  static constexpr int kResumeFrames = 30;

  // `reference_frame_bgr`: the frame the stored reference was taken from; its slice is the
  // context's.
  ResumeMode(const ModeContext& context, cv::Mat reference_frame_bgr)
      : context_(context), reference_frame_(std::move(reference_frame_bgr)) {}

  AgentMode kind() const override { return AgentMode::kIdle; }
  void Enter(const CapturedFrame& /*frame*/, const ServoTargets& current) override {
    hold_ = current;  // no servo moves until the view is found
  }
  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;

 private:
  const ModeContext& context_;
  cv::Mat reference_frame_;  // BGR, as stored
  ServoTargets hold_;        // [deg]
  int frames_left_ = kResumeFrames;
  double best_confidence_ = 0;
};

}  // namespace kapfix::agent
