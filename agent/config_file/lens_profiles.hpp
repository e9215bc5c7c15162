#pragma once

// The configuration file's "lenses": each profile is a kapfix.v1.LensProfile in protobuf's
// JSON mapping — its name and optics under the settings' field names and ranges, so a new
// optic is a field of the message with nothing to add here — plus its deg/px when given
// directly (deg_per_px_pan, deg_per_px_tilt: measured or known, not settings).

#include <nlohmann/json.hpp>
#include <string>

#include "agent/config/agent_config.hpp"

namespace kapfix::agent {

// Replaces config->lenses with the profiles of `lenses` (a JSON array) and fits the first one
// unless config->lens names one of them. False with "lenses[i]…: <reason>" at the first
// entry that is not an object, has an unknown key, a wrong type or a value out of range.
bool ReadLensProfiles(const nlohmann::json& lenses, AgentConfig* config, std::string* error);

}  // namespace kapfix::agent
