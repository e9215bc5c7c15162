#include "agent/resume/stored_settings.hpp"

#include <spdlog/spdlog.h>

#include "agent/commands/settings_messages.hpp"
#include "agent/server/command_validator.hpp"

namespace kapfix::agent {

bool ApplyStoredSettings(const std::vector<kapfix::v1::Command>& settings, AgentConfig* config,
                         std::string* error) {
  const CommandValidator validator;
  AgentConfig updated = *config;
  for (const kapfix::v1::Command& command : settings) {
    kapfix::v1::AgentState current;
    FillSettings(updated, &current);
    current.set_slice(1);
    const kapfix::v1::Reply reply = validator.Validate(command, current);
    if (!reply.ok()) {
      if (error) *error = "stored setting refused: " + reply.reason();
      return false;
    }
    std::string why;
    if (!ApplySettingsCommand(command, &updated, &why)) {
      if (error) {
        const auto* field = command.GetDescriptor()->FindFieldByNumber(command.command_case());
        *error =
            "stored setting refused: " + (field ? field->name() : std::string("?")) + ": " + why;
      }
      return false;
    }
  }
  *config = std::move(updated);
  return true;
}

std::optional<ResumeRecord> LoadResumeRecord(ResumeStore& store, AgentConfig* config) {
  std::string why;
  std::optional<ResumeRecord> record;
  try {
    record = store.Load(&why);
    if (record && !ApplyStoredSettings(record->settings, config, &why)) record.reset();
  } catch (const std::exception& e) {
    record.reset();
    why = store.file().string() + ": " + e.what();
  }
  if (!record && !why.empty()) {
    const std::filesystem::path aside = store.SetAside();
    spdlog::error("not resumed: {}; {}; starting from the configuration", why,
                  aside.empty() ? std::string("it could not be set aside")
                                : "set aside as " + aside.string());
  }
  return record;
}

}  // namespace kapfix::agent
