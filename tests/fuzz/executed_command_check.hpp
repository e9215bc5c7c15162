#pragma once

// What the agent promises about every command that reaches AgentControl::Execute (SPEC §2.8,
// §5; issue 5), stated apart from CommandValidator so that the fuzzer checks the validator
// instead of repeating it: every number is finite and within its settings-schema range, every enum
// is a value this build knows, every size and index fits the agent's state.

#include "agent/server/command_validator.hpp"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/state.pb.h"

namespace kapfix::fuzz {

// Aborts (Broken) naming the field when `command` breaks the promise. `before` is the state
// the command was validated against; it must give the frame size and slice count.
void RequireWithinLimits(const kapfix::v1::Command& command, const kapfix::v1::AgentState& before,
                         const kapfix::agent::CommandLimits& limits);

}  // namespace kapfix::fuzz
