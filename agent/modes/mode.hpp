#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>

#include "agent/capture/frame_source.hpp"
#include "agent/modes/agent_mode.hpp"
#include "agent/modes/frame_processor.hpp"

namespace kapfix::agent {

// A view fixated earlier that fixate takes up again (after an SSP started while fixating, or a
// resume that found its stored view), instead of a new reference from the frame in front of
// the camera.
struct HeldView {
  cv::Mat reference_frame;  // BGR, as it was taken
  std::uint64_t reference_index = 0;
  int slice = 0;                       // [1..slice_count]
  std::optional<cv::Point> seek_from;  // [px] where the view was found (a resume)
  // [px] where reference_index's frame shows the held view (stored-reference convention): 0
  // for a view taken from that frame; a view resumed after a restart is the stored frame's,
  // found displaced by this in the frame that resumed it.
  cv::Point2d seen_at{0, 0};
};

// How a mode ended by itself (deadline reached, calibration done, view found or not): what
// ModeRunner switches to.
struct ModeEnd {
  std::optional<HeldView> fixate;  // fixate this view next; none: idle
  ServoTargets hold;               // [deg] where idle holds the servos
  std::optional<bool> resumed;     // a resume ended: found (true) or not (ModeEvents)
};

// One of the agent's modes (SPEC §4) as a strategy of ModeRunner: it owns its state (the
// fixation loop, a selection run, a calibration) and runs on the control thread only. The
// runner enters it, gives it every frame, tells it of new settings, and switches away when it
// ends (TakeEnd) or another mode is asked for.
class Mode {
 public:
  virtual ~Mode() = default;

  virtual AgentMode kind() const = 0;
  // The mode starts on `frame`, seen through the servo angles `current` [deg]. Throws
  // std::runtime_error (or std::invalid_argument) when it cannot start on it: the runner then
  // holds the servos idle and says why.
  virtual void Enter(const CapturedFrame& frame, const ServoTargets& current) = 0;
  // Right after Enter, when the camera ran before: the frame it showed just before the one
  // the mode entered on. A fixation judges from it how fast the view moved as its reference
  // was taken; the other modes have no use for it.
  virtual void SeeBefore(const CapturedFrame& /*frame*/) {}
  virtual FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                               double dt_s) = 0;
  // The settings or the slice changed (ModeContext); `rebuild`: more than the controller's
  // gains did. Throws like Enter.
  virtual void OnSettings(bool /*rebuild*/) {}
  // The fixation an SSP started now keeps to go back to when it ends (issue 14).
  virtual std::optional<HeldView> HeldFixation() const { return std::nullopt; }

  // Once, after the Process call in which the mode ended by itself.
  std::optional<ModeEnd> TakeEnd() { return std::exchange(end_, std::nullopt); }

 protected:
  void Finish(ModeEnd end) { end_ = std::move(end); }

 private:
  std::optional<ModeEnd> end_;
};

}  // namespace kapfix::agent
