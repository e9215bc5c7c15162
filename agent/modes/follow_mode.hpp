#pragma once

#include "agent/modes/fixate_mode.hpp"

namespace kapfix::agent {

// Follow (SPEC §4): fixate's loop, each frame matched against the previous one (a moving
// boat); no stored view to come back to.
class FollowMode : public FixateMode {
 public:
  explicit FollowMode(ModeContext& context) : FixateMode(context, AgentMode::kFollow) {}
};

}  // namespace kapfix::agent
