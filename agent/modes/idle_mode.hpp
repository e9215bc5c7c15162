#pragma once

#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"

namespace kapfix::agent {

// Idle (SPEC §4): the servos hold where they were when idle began; nothing is measured.
class IdleMode : public Mode {
 public:
  // `hold` [deg]: where the servos stay until Enter (a mode that ended hands over its own).
  IdleMode(const ModeContext& context, const ServoTargets& hold) : context_(context), hold_(hold) {}

  AgentMode kind() const override { return AgentMode::kIdle; }
  void Enter(const CapturedFrame& /*frame*/, const ServoTargets& current) override {
    hold_ = current;
  }
  FrameOutcome Process(const CapturedFrame& /*frame*/, const ServoTargets& /*current*/,
                       double /*dt_s*/) override {
    return context_.Hold(AgentMode::kIdle, hold_);
  }

 private:
  const ModeContext& context_;
  ServoTargets hold_;  // [deg]
};

}  // namespace kapfix::agent
