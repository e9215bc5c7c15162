#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "agent/config/agent_config.hpp"
#include "agent/modes/agent_mode.hpp"
#include "agent/modes/fixate_mode.hpp"
#include "agent/modes/frame_processor.hpp"
#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"
#include "agent/modes/mode_events.hpp"

namespace kapfix::agent {

// The agent's modes (SPEC §4) on the control thread: one FrameProcessor that runs the mode in
// force (idle, calibrate, PSS, SSP, fixate, follow, free-swing recording, or a resume; each a
// Mode of its own) on each frame and switches between them. Mode switches, settings and the
// slice are requested from any thread and applied between frames, so the modes are only ever
// touched by the control thread. Results leave through ModeEvents.
class ModeRunner : public FrameProcessor {
 public:
  // `settings` must be IsValid. Throws std::runtime_error when its strategy or controller
  // cannot be built.
  // `settings`: the owner's immutable snapshot (StateKeeper::settings()), held, not copied.
  ModeRunner(std::shared_ptr<const AgentConfig> settings, ModeRunnerOptions options,
             ModeEvents& events);
  ModeRunner(const AgentConfig& settings, ModeRunnerOptions options, ModeEvents& events)
      : ModeRunner(std::make_shared<const AgentConfig>(settings), std::move(options), events) {}

  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;

  // Any thread; applied before the next frame. A later request of the same kind replaces an
  // earlier one not yet applied.
  void RequestMode(AgentMode mode, std::optional<SwingDeadline> deadline = std::nullopt);
  // The owner's new snapshot (must be IsValid).
  void RequestSettings(std::shared_ptr<const AgentConfig> settings);
  void RequestSettings(const AgentConfig& settings) {
    RequestSettings(std::make_shared<const AgentConfig>(settings));
  }
  // [1..slice_count] fixate on this slice: the current fixation moves to it, any other mode
  // (SSP finished, idle) switches to fixate.
  void RequestSlice(int slice);
  // Any thread, before the first frame: come back fixating the view an earlier run held
  // (issue 14), instead of the start mode. `reference_frame_bgr` is the frame its reference
  // was taken from, `slice` [1..slice_count] its slice. The servos hold while the stored patch
  // is searched over the whole frame (ResumeMode); found with enough confidence, the loop
  // closes from where it was found (fixate); not found within ResumeMode::kResumeFrames, the
  // agent stays idle and says so. Either way events.OnResumeEnded tells.
  void RequestResume(cv::Mat reference_frame_bgr, int slice);

  // On the control thread: waits until the modes' slow jobs (a recording being written) are
  // done and delivers their events. Process delivers them anyway, without waiting.
  void FlushWork();

  AgentMode mode() const { return mode_.load(); }
  int slice() const { return context_.slice(); }

 private:
  struct Pending {
    std::optional<std::pair<AgentMode, SwingDeadline>> mode;
    std::shared_ptr<const AgentConfig> settings;  // null: no change
    std::optional<int> slice;
    std::optional<std::pair<cv::Mat, int>> resume;  // reference frame, slice
  };

  void ApplyPending(const CapturedFrame& frame, const ServoTargets& current);
  // The operator's (or the start's) mode; throws when it cannot start on `frame`. `slice` says
  // whether the operator picked the slice with this request (fixate keeps it then).
  void Enter(AgentMode mode, const SwingDeadline& deadline, FixateMode::SliceChoice slice,
             const CapturedFrame& frame, const ServoTargets& current);
  std::unique_ptr<Mode> MakeMode(AgentMode mode, const SwingDeadline& deadline,
                                 FixateMode::SliceChoice slice);
  // The mode in force ended by itself on `frame`, whose outcome it gave.
  FrameOutcome SwitchAfter(ModeEnd end, FrameOutcome outcome, const CapturedFrame& frame,
                           const ServoTargets& current, double dt_s);
  void SwitchToIdle(const ServoTargets& hold);
  void SetMode(AgentMode mode);

  ModeContext context_;  // control thread only, but for the slice
  std::atomic<AgentMode> mode_{AgentMode::kIdle};

  std::mutex pending_mutex_;
  Pending pending_;

  std::unique_ptr<Mode> current_;  // control thread only
  // The frame processed last (control thread only): the frame before the one a mode enters
  // on (Mode::SeeBefore). Its image is shared, not copied: a frame owns its image.
  std::optional<CapturedFrame> previous_;
  bool resuming_ = false;  // current_ is a ResumeMode
};

}  // namespace kapfix::agent
