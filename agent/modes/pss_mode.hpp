#pragma once

#include <memory>
#include <optional>

#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"
#include "agent/modes/swing_window.hpp"
#include "common/selection/patch_size_selection_run.hpp"

namespace kapfix::agent {

// PSS, patch size selection (SPEC §2.5): the servos hold while a free swing is measured with
// each candidate size that fits the frame; reports its progress and, at the deadline, the
// recommended size; then idle.
class PssMode : public Mode {
 public:
  PssMode(ModeContext& context, SwingWindow window) : context_(context), window_(window) {}

  AgentMode kind() const override { return AgentMode::kPss; }
  void Enter(const CapturedFrame& frame, const ServoTargets& current) override;
  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;

 private:
  ModeContext& context_;
  SwingWindow window_;
  ServoTargets hold_;                               // [deg]
  std::shared_ptr<const SearchStrategy> strategy_;  // the one the run started with
  std::optional<PatchSizeSelectionRun> run_;
};

}  // namespace kapfix::agent
