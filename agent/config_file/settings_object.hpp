#pragma once

// The configuration file's "settings" object: the operator settings as the kapfix.v1 settings
// messages in protobuf's JSON mapping. Its keys are the settings commands (Command fields that
// carry a setting) without their "set_": {"gains": {"p": 0.8}, "search": {"axis": "AXIS_BOTH"}}.
// Each is applied as that command would be (ApplySettingsCommand), so the file, the command server,
// kapfix-ctl and the station give an out-of-range value the same reason; a new settings command is
// a new key here with nothing to add.

#include <nlohmann/json.hpp>
#include <string>

#include "agent/config/agent_config.hpp"

namespace kapfix::agent {

// Applies every key of `settings` to `config`. False with "settings.<key>.<field>: <reason>"
// at the first unknown key, wrong JSON type, unknown enum name or out-of-range value.
bool ApplySettingsObject(const nlohmann::json& settings, AgentConfig* config, std::string* error);

}  // namespace kapfix::agent
