#pragma once

#include <atomic>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "agent/config/agent_config.hpp"
#include "agent/modes/agent_mode.hpp"
#include "agent/modes/frame_processor.hpp"
#include "agent/modes/mode_events.hpp"
#include "agent/worker/work_queue.hpp"
#include "common/control/predictive_controller.hpp"
#include "common/control/servo_belief.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix::agent {

struct ModeRunnerOptions {
  AgentMode start_mode = AgentMode::kFixate;  // entered on the first frame
  SwingDeadline default_deadline;             // PSS, SSP and recording without their own
  PredictiveOptions predictive;               // the swing model of the predictive controller
  int actuation_delay_frames = 2;             // [frames] calibration waits this + 1 per move
  double frame_period_s = 1.0 / 30;           // [s] camera time of one frame (deadlines)
  std::string recordings_dir;                 // free-swing recordings; empty = none allowed
  // Where the modes' disk writes go (free-swing recordings), off the control thread; their
  // results come back through ModeRunner::Process. None: the runner makes its own.
  std::shared_ptr<WorkQueue> worker;
  // The pipeline's belief of the angles each frame was seen through: set, the fixation
  // controller acts on it as resolved from each frame's measurement (ServoBeliefController),
  // which picks the command in effect when the servo latency jitters. None: the controller
  // acts on the `current` angles it is given.
  std::shared_ptr<ServoBelief> servo_belief;
};

// What all modes share, owned by ModeRunner on the control thread: the settings snapshot in
// force, the search strategy built from it, the slice in use, the runner's options and where
// results go. The slice is also read from other threads (ModeRunner::slice()).
class ModeContext {
 public:
  // `settings` must be IsValid. Throws std::runtime_error when their strategy or controller
  // cannot be built.
  ModeContext(std::shared_ptr<const AgentConfig> settings, ModeRunnerOptions options,
              ModeEvents& events);

  const AgentConfig& settings() const { return *settings_; }
  // The owner's new snapshot, or a calibrated copy (must be IsValid). Rebuild() makes the
  // strategy of new search settings.
  void SetSettings(std::shared_ptr<const AgentConfig> settings) { settings_ = std::move(settings); }
  // The search strategy of the settings, and a check that their controller can be built.
  // Throws std::runtime_error ("search: ..." or "controller: ...").
  void Rebuild();
  // The strategy built by the last Rebuild: selection runs keep the one they started with.
  const std::shared_ptr<const SearchStrategy>& strategy() const { return strategy_; }
  // A fixation loop on the slice in use with the settings' controller. Throws like Rebuild.
  std::unique_ptr<FixationLoop> MakeLoop(FixationOptions::Reference reference) const;

  int slice() const { return slice_.load(); }
  void SetSlice(int slice) { slice_ = slice; }
  // [1..slices] `slice` clamped to the settings' slice count.
  int ClampSlice(int slice) const;
  // SSP's last ranking, best first (control thread only); empty before any SSP has finished.
  const std::vector<int>& slice_ranking() const { return slice_ranking_; }
  void SetSliceRanking(std::vector<int> ranking) { slice_ranking_ = std::move(ranking); }

  const ModeRunnerOptions& options() const { return options_; }
  ModeEvents& events() const { return events_; }
  WorkQueue& worker() const { return *options_.worker; }

  // The single-channel plane the settings search in.
  cv::Mat Plane(const cv::Mat& frame_bgr) const;
  // [px] the patch of the slice in use in a frame of this size.
  cv::Rect SlicePatchRect(cv::Size frame) const;
  // The outcome of a frame on which `mode` measured nothing: the servos stay at `targets`.
  FrameOutcome Hold(AgentMode mode, const ServoTargets& targets) const;

 private:
  ModeRunnerOptions options_;
  ModeEvents& events_;
  std::shared_ptr<const AgentConfig> settings_;
  std::shared_ptr<const SearchStrategy> strategy_;
  std::atomic<int> slice_{0};
  std::vector<int> slice_ranking_;
};

}  // namespace kapfix::agent
