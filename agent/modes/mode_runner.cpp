#include "agent/modes/mode_runner.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "agent/modes/calibrate_mode.hpp"
#include "agent/modes/fixate_mode.hpp"
#include "agent/modes/follow_mode.hpp"
#include "agent/modes/free_swing_recording_mode.hpp"
#include "agent/modes/idle_mode.hpp"
#include "agent/modes/pss_mode.hpp"
#include "agent/modes/resume_mode.hpp"
#include "agent/modes/run_options.hpp"
#include "agent/modes/ssp_mode.hpp"
#include "agent/modes/swing_window.hpp"

namespace kapfix::agent {

ModeRunner::ModeRunner(std::shared_ptr<const AgentConfig> settings, ModeRunnerOptions options,
                       ModeEvents& events)
    : context_(std::move(settings), std::move(options), events),
      current_(std::make_unique<IdleMode>(context_, ServoTargets{})) {
  pending_.mode =
      std::make_pair(context_.options().start_mode, context_.options().default_deadline);
}

void ModeRunner::RequestMode(AgentMode mode, std::optional<SwingDeadline> deadline) {
  std::lock_guard lock(pending_mutex_);
  pending_.mode = std::make_pair(mode, deadline.value_or(context_.options().default_deadline));
}

void ModeRunner::RequestSettings(std::shared_ptr<const AgentConfig> settings) {
  std::lock_guard lock(pending_mutex_);
  pending_.settings = std::move(settings);
}

void ModeRunner::RequestSlice(int slice) {
  std::lock_guard lock(pending_mutex_);
  pending_.slice = slice;
}

void ModeRunner::RequestResume(cv::Mat reference_frame_bgr, int slice) {
  std::lock_guard lock(pending_mutex_);
  pending_.resume = std::make_pair(std::move(reference_frame_bgr), slice);
  pending_.mode.reset();  // the resume decides: fixate when the view is found, else idle
}

void ModeRunner::SetMode(AgentMode mode) {
  mode_ = mode;
  context_.events().OnModeChanged(mode, context_.slice());
}

void ModeRunner::SwitchToIdle(const ServoTargets& hold) {
  current_ = std::make_unique<IdleMode>(context_, hold);
  resuming_ = false;
  SetMode(AgentMode::kIdle);
}

void ModeRunner::ApplyPending(const CapturedFrame& frame, const ServoTargets& current) {
  Pending pending;
  {
    std::lock_guard lock(pending_mutex_);
    std::swap(pending, pending_);
  }
  bool rebuild = false;
  const bool new_settings = pending.settings != nullptr;
  if (pending.resume) {
    context_.SetSlice(context_.ClampSlice(pending.resume->second));
    current_ = std::make_unique<ResumeMode>(context_, std::move(pending.resume->first));
    current_->Enter(frame, current);
    resuming_ = true;
    spdlog::info(
        "resuming: searching the whole frame for the view of slice {} held before the "
        "restart; the servos hold until it is found",
        context_.slice());
  }
  if (new_settings) {
    rebuild = !SameLoop(context_.settings(), *pending.settings);
    context_.SetSettings(std::move(pending.settings));
    context_.SetSlice(context_.ClampSlice(context_.slice()));
  }
  if ((pending.slice || pending.mode) && resuming_) {
    // The operator decides instead.
    current_ = std::make_unique<IdleMode>(context_, current);
    resuming_ = false;
  }
  if (pending.slice) {
    // Picking a slice means fixating on it (the operator confirms SSP's choice or overrides
    // it): a fixation in progress keeps its reference frame and moves to the new patch; any
    // other mode hands over to fixate.
    context_.SetSlice(context_.ClampSlice(*pending.slice));
    rebuild = true;
    const AgentMode now = mode_;
    if (!pending.mode && now != AgentMode::kFixate && now != AgentMode::kFollow) {
      pending.mode = std::make_pair(AgentMode::kFixate, context_.options().default_deadline);
    } else {
      context_.events().OnModeChanged(now, context_.slice());
    }
  }
  try {
    if (rebuild) {
      context_.Rebuild();
      current_->OnSettings(true);
    } else if (new_settings) {
      current_->OnSettings(false);  // bumpless: the controller keeps its state
    }
    if (pending.mode) {
      // Confirming SSP's recommendation (the station's Confirm) accepts the agent's choice,
      // so a weak patch there gives way along SSP's ranking; any other pick is the operator's.
      const std::vector<int>& ranking = context_.slice_ranking();
      const bool confirms_ssp = !ranking.empty() && context_.slice() == ranking.front();
      const FixateMode::SliceChoice choice = pending.slice && !confirms_ssp
                                                 ? FixateMode::SliceChoice::kOperators
                                                 : FixateMode::SliceChoice::kAgents;
      Enter(pending.mode->first, pending.mode->second, choice, frame, current);
    }
  } catch (const std::exception& e) {
    // A setting that cannot work with this camera (a patch larger than the frame) or a
    // strategy that cannot be built: hold still and say why rather than fly blind.
    spdlog::error("cannot {}: {}; the agent is idle",
                  pending.mode ? std::string(ToString(pending.mode->first)) : "apply settings",
                  e.what());
    SwitchToIdle(current);
  }
}

std::unique_ptr<Mode> ModeRunner::MakeMode(AgentMode mode, const SwingDeadline& deadline,
                                           FixateMode::SliceChoice slice) {
  const SwingWindow window{
      .deadline = deadline, .start_index = 0, .frame_period_s = context_.options().frame_period_s};
  switch (mode) {
    case AgentMode::kIdle:
      return std::make_unique<IdleMode>(context_, ServoTargets{});
    case AgentMode::kFixate:
      return std::make_unique<FixateMode>(context_, slice);
    case AgentMode::kFollow:
      return std::make_unique<FollowMode>(context_);
    case AgentMode::kSsp:
      // SSP started while fixating keeps that fixation to go back to (SSP restarted keeps it
      // too); anything else drops it.
      return std::make_unique<SspMode>(context_, window, current_->HeldFixation());
    case AgentMode::kPss:
      return std::make_unique<PssMode>(context_, window);
    case AgentMode::kCalibrate:
      return std::make_unique<CalibrateMode>(context_);
    case AgentMode::kRecordFreeSwing:
      return std::make_unique<FreeSwingRecordingMode>(context_, window);
  }
  throw std::runtime_error("unknown mode");
}

void ModeRunner::Enter(AgentMode mode, const SwingDeadline& deadline, FixateMode::SliceChoice slice,
                       const CapturedFrame& frame, const ServoTargets& current) {
  std::unique_ptr<Mode> next = MakeMode(mode, deadline, slice);
  current_.reset();  // what the previous mode held goes before the next one starts
  resuming_ = false;
  next->Enter(frame, current);
  if (previous_ && previous_->index + 1 == frame.index) next->SeeBefore(*previous_);
  current_ = std::move(next);
  spdlog::info("mode {}{}", ToString(mode),
               mode == AgentMode::kFixate || mode == AgentMode::kFollow
                   ? " on slice " + std::to_string(context_.slice())
                   : std::string());
  SetMode(mode);
}

FrameOutcome ModeRunner::SwitchAfter(ModeEnd end, FrameOutcome outcome, const CapturedFrame& frame,
                                     const ServoTargets& current, double dt_s) {
  if (!end.fixate) {
    SwitchToIdle(end.hold);
    if (end.resumed) context_.events().OnResumeEnded(*end.resumed);
    return outcome;
  }
  context_.SetSlice(end.fixate->slice);
  auto fixate = std::make_unique<FixateMode>(context_);
  try {
    fixate->TakeUp(*end.fixate);
  } catch (const std::exception& e) {
    spdlog::error("{}: {}; the agent is idle", end.resumed ? "not resumed" : "cannot fixate again",
                  e.what());
    SwitchToIdle(end.hold);
    if (end.resumed) context_.events().OnResumeEnded(false);
    return outcome;
  }
  current_ = std::move(fixate);
  resuming_ = false;
  SetMode(AgentMode::kFixate);
  if (!end.resumed) return outcome;
  context_.events().OnResumeEnded(true);
  return current_->Process(frame, current, dt_s);  // the frame the view was found in
}

void ModeRunner::FlushWork() {
  context_.worker().Flush();
  context_.worker().Deliver();
}

FrameOutcome ModeRunner::Process(const CapturedFrame& frame, const ServoTargets& current,
                                 double dt_s) {
  context_.worker().Deliver();  // what the worker finished, as events of this thread
  ApplyPending(frame, current);
  FrameOutcome outcome = current_->Process(frame, current, dt_s);
  previous_ = frame;
  if (std::optional<ModeEnd> end = current_->TakeEnd()) {
    return SwitchAfter(std::move(*end), outcome, frame, current, dt_s);
  }
  return outcome;
}

}  // namespace kapfix::agent
