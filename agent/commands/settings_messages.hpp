#pragma once

#include <string>

#include "agent/config/agent_config.hpp"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/state.pb.h"

namespace kapfix::agent {

// The operator-settable part of AgentConfig as kapfix.v1 messages (SPEC §6), both ways.

// Fills the settings fields of `state` (gains, search, camera, lens, photo settings, video)
// from `config`; every field present.
void FillSettings(const AgentConfig& config, kapfix::v1::AgentState* state);

// Whether `command` is a settings command, i.e. one ApplySettingsCommand takes.
bool IsSettingsCommand(const kapfix::v1::Command& command);

// Applies the settings command (set_gains, set_search, set_camera, set_lens, set_video or
// set_photo) to `config`: absent fields keep their values (partial
// update), then the whole config must be IsValid. False with the reason, `config` untouched,
// when it is not; also false for a command that is not a settings command.
bool ApplySettingsCommand(const kapfix::v1::Command& command, AgentConfig* config,
                          std::string* error);

}  // namespace kapfix::agent
