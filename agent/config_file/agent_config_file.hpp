#pragma once

// kapfix-agent's configuration file (SPEC §4; issue 11): one JSON object. Its "settings"
// object holds the operator settings as the kapfix.v1 settings messages in protobuf's JSON
// mapping, keyed by the settings command that carries them without its "set_" ("gains",
// "search", …: see settings_object.hpp); the
// other keys are the devices, the link, the folders and the lens profiles
// (agent/config/agent_config.hpp). Every key: resources/README.md.

#include <string>

#include "agent/config/agent_config.hpp"

namespace kapfix::agent {

// Parses a configuration from JSON text: keys not given keep their defaults; unknown keys,
// wrong types and invalid values are errors "line N: <field>: <reason>" (the line of the
// field's key when it can be found), invalid JSON an error with line and column. `config` is
// only written on success.
bool ParseAgentConfig(const std::string& json_text, AgentConfig* config, std::string* error);

// Reads and parses a configuration file; errors are "<path>:<line>: <field>: <reason>"
// ("<path>: …" when no line applies).
bool LoadAgentConfig(const std::string& path, AgentConfig* config, std::string* error);

}  // namespace kapfix::agent
