#pragma once

#include <memory>
#include <optional>

#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"
#include "agent/modes/swing_window.hpp"
#include "common/selection/slice_selection_run.hpp"

namespace kapfix::agent {

// SSP, slice selection (SPEC §2.6): the servos hold while a free swing is measured in every
// slice; reports its progress and, at the deadline, the recommended slice. Started while
// fixating, it goes back to that fixation at the end until the operator confirms a slice
// (issue 14); otherwise it ends idle on the recommended slice.
class SspMode : public Mode {
 public:
  // `held`: the fixation to go back to (Mode::HeldFixation of the mode it interrupts).
  SspMode(ModeContext& context, SwingWindow window, std::optional<HeldView> held)
      : context_(context), window_(window), held_(std::move(held)) {}

  AgentMode kind() const override { return AgentMode::kSsp; }
  void Enter(const CapturedFrame& frame, const ServoTargets& current) override;
  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;
  // SSP restarted while running still goes back to the fixation before it.
  std::optional<HeldView> HeldFixation() const override { return held_; }

 private:
  ModeContext& context_;
  SwingWindow window_;
  std::optional<HeldView> held_;
  ServoTargets hold_;  // [deg]
  // The strategy the run started with: a settings change during the run does not replace it.
  std::shared_ptr<const SearchStrategy> strategy_;
  std::optional<SliceSelectionRun> run_;
};

}  // namespace kapfix::agent
