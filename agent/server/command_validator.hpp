#pragma once

// Range checks of every field of a Command before anything can reach a servo (SPEC §2.8, §5;
// issue 5). A proto3 message accepts any float, including NaN and ±inf, and any integer in an
// enum field, so nothing a station sends is trusted until it has passed here.

#include <cstdint>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/state.pb.h"

namespace kapfix::agent {

// What the settings schema (kapfix/v1/settings_schema.hpp) does not say: the ranges of a
// setting live in its field's option, not here.
struct CommandLimits {
  std::uint32_t max_lens_name_chars = 64;     // [chars] the name becomes a file name
  std::uint32_t max_photo_note_bytes = 1024;  // [bytes]
  // Used when the agent's state does not say (frame size 0, no slice count yet).
  std::uint32_t fallback_frame_side_px = 1600;  // [px] largest camera frame of SPEC §1
  std::uint32_t fallback_slice_count = 9;       // [count] the thesis's N
};

class CommandValidator {
 public:
  explicit CommandValidator(CommandLimits limits = {});

  // A Reply with ok = true when every present field is in range. Otherwise ok = false, error
  // ERROR_CODE_UNKNOWN_COMMAND (no command set, or one newer than this agent) or
  // ERROR_CODE_OUT_OF_RANGE, and a reason naming the field, the value and the range (the
  // schema's one reason, kapfix::v1::OutOfRangeReason), e.g.
  // "set_gains.p = nan: must be a finite number in [0.01, 10]". `current` gives what ranges
  // depend on: the frame size (patch size, search range, slice count) and the slice count
  // (select_slice). Header and command_sequence are left to the caller.
  kapfix::v1::Reply Validate(const kapfix::v1::Command& command,
                             const kapfix::v1::AgentState& current) const;

  // Whether Validate reads `current` for this command: select_slice, and a settings command
  // whose message has a field capped by the frame or bounded by another field (the schema's
  // frame_side and at_most). The others are validated against an empty state, so the caller
  // need not take a snapshot of the agent's state for them.
  static bool NeedsState(const kapfix::v1::Command& command);

  const CommandLimits& limits() const { return limits_; }

 private:
  CommandLimits limits_;
};

}  // namespace kapfix::agent
