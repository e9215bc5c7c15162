#pragma once

#include <optional>
#include <string>
#include <vector>

#include "agent/config/agent_config.hpp"
#include "agent/resume/resume_store.hpp"
#include "kapfix/v1/command.pb.h"

namespace kapfix::agent {

// Applies the settings commands a ResumeRecord stored over `config`, in order, each through
// the same checks as a station's command: the schema's range check (CommandValidator, against
// the state `config` gives: frame size, slice count), then ApplySettingsCommand. False with
// the reason naming the command and the field at the first that fails; `config` untouched
// then.
bool ApplyStoredSettings(const std::vector<kapfix::v1::Command>& settings, AgentConfig* config,
                         std::string* error);

// What a restart resumes from: the stored record with its settings applied to `config`.
// Nothing stored: nullopt. A record that cannot be read or whose settings fail the check is
// set aside (ResumeStore::SetAside) with one log line naming the problem, and nullopt:
// the agent starts from `config` as it is. Never throws.
std::optional<ResumeRecord> LoadResumeRecord(ResumeStore& store, AgentConfig* config);

}  // namespace kapfix::agent
