#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "agent/config/agent_config.hpp"
#include "agent/modes/agent_mode.hpp"
#include "agent/modes/calibration_run.hpp"
#include "agent/modes/mode_events.hpp"
#include "agent/modes/report_messages.hpp"
#include "agent/pipeline/frame_processor.hpp"
#include "common/control/predictive_controller.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/selection/patch_size_selection_run.hpp"
#include "common/selection/slice_selection_run.hpp"

namespace kapfix::agent {

struct ModeRunnerOptions {
  AgentMode start_mode = AgentMode::kFixate;  // entered on the first frame
  SwingDeadline default_deadline;             // PSS, SSP and recording without their own
  PredictiveOptions predictive;               // the swing model of the predictive controller
  int actuation_delay_frames = 2;             // [frames] calibration waits this + 1 per move
  double frame_period_s = 1.0 / 30;           // [s] camera time of one frame (deadlines)
  std::string recordings_dir;                 // free-swing recordings; empty = none allowed
};

// The agent's modes (SPEC §4) on the control thread: one FrameProcessor that runs idle,
// calibrate, PSS, SSP, fixate, follow or free-swing recording on each frame. Mode switches,
// settings and the slice are requested from any thread and applied between frames, so the
// fixation loop, the selection runs and the calibration are only ever touched by the control
// thread. Results leave through ModeEvents.
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
  // is searched over the whole frame (ResumeSearch); found with enough confidence, the loop
  // closes from where it was found (fixate); not found within kResumeFrames, the agent stays
  // idle and says so. Either way events.OnResumeEnded tells.
  void RequestResume(cv::Mat reference_frame_bgr, int slice);

  AgentMode mode() const { return mode_.load(); }
  int slice() const { return slice_.load(); }

 private:
  struct Pending {
    std::optional<std::pair<AgentMode, SwingDeadline>> mode;
    std::shared_ptr<const AgentConfig> settings;  // null: no change
    std::optional<int> slice;
    std::optional<std::pair<cv::Mat, int>> resume;  // reference frame, slice
  };
  // A resume under way: the stored view being searched for, the servos holding.
  struct Resume {
    cv::Mat reference_frame;  // BGR, as stored
    int frames_left = 0;      // [frames] searched before giving up
    double best_confidence = 0;
  };
  // The fixation SSP interrupted: after SSP the agent goes back to it until the operator
  // confirms a slice (issue 14).
  struct HeldFixation {
    cv::Mat reference_frame;
    std::uint64_t reference_index = 0;
    int slice = 0;
  };

  void ApplyPending(const CapturedFrame& frame, const ServoTargets& current);
  void Rebuild();
  void Enter(AgentMode mode, const SwingDeadline& deadline, const CapturedFrame& frame,
             const ServoTargets& current);
  void SetMode(AgentMode mode);
  bool SwingDeadlineReached(std::uint64_t index) const;
  SwingProgress ProgressOf(int frames_used, bool done) const;
  FrameOutcome Fixate(const CapturedFrame& frame, const ServoTargets& current, double dt_s);
  FrameOutcome ResumeSearch(const CapturedFrame& frame, const ServoTargets& current, double dt_s);
  FrameOutcome SelectSlice(const cv::Mat& plane, std::uint64_t index);
  FrameOutcome SelectPatchSize(const cv::Mat& plane, std::uint64_t index);
  FrameOutcome Calibrate(const cv::Mat& plane);
  FrameOutcome RecordFreeSwing(const cv::Mat& plane, const CapturedFrame& frame);
  FrameOutcome Hold(AgentMode mode) const;
  cv::Rect SlicePatchRect(cv::Size frame) const;
  FixationOptions MakeFixationOptions(AgentMode mode) const;

  ModeRunnerOptions options_;
  ModeEvents& events_;
  std::atomic<AgentMode> mode_{AgentMode::kIdle};
  std::atomic<int> slice_{0};

  std::mutex pending_mutex_;
  Pending pending_;
  bool started_ = false;

  // Control thread only. The owner's snapshot, never changed in place: a finished
  // calibration makes a new one the same way the owner does (ApplyLensCalibration).
  std::shared_ptr<const AgentConfig> settings_;
  std::shared_ptr<const SearchStrategy> strategy_;
  // The strategy a selection run or calibration was started with: a settings change during
  // the run replaces strategy_, not this one.
  std::shared_ptr<const SearchStrategy> run_strategy_;
  std::unique_ptr<FixationLoop> loop_;
  bool lock_lost_ = false;             // the last fixating frame's lock state, to log its changes
  cv::Mat reference_frame_;            // fixate / follow: the frame the reference was taken from
  std::uint64_t reference_index_ = 0;  // its index
  ServoTargets hold_{};                // [deg] where the servos stay during a free swing
  SwingDeadline deadline_;
  std::uint64_t swing_start_index_ = 0;
  std::optional<SliceSelectionRun> slice_run_;
  std::optional<PatchSizeSelectionRun> pss_run_;
  std::optional<CalibrationRun> calibration_;
  int calibration_progress_ = -1;                           // moves_done last reported
  std::vector<std::pair<std::int64_t, double>> recording_;  // [µs, px] free swing samples
  cv::Mat previous_plane_;
  std::optional<SampleSet> recording_samples_;
  std::optional<Resume> resume_;
  std::optional<HeldFixation> held_fixation_;
};

}  // namespace kapfix::agent
