#include "agent/setting_flags.hpp"

#include "agent/commands/settings_messages.hpp"

namespace kapfix::agent {
namespace {

// "settings.photo.window_s": where the configuration file holds the setting.
std::string FileKeyOf(const kapfix::v1::SettingEntry& entry) {
  std::string group = entry.command_field->name();
  if (group.starts_with("set_")) group.erase(0, 4);
  if (entry.field == entry.command_field) return "settings." + group;
  return "settings." + group + "." + entry.field->name();
}

}  // namespace

SettingFlags::SettingFlags(CLI::App& app) {
  for (const kapfix::link::SettingKey& key : kapfix::link::SettingKeys()) {
    if (!key.entry.options->flag().empty()) flags_.push_back({&key, nullptr, {}});
  }
  // flags_ no longer grows: the options may hold its elements' addresses.
  for (Flag& flag : flags_) {
    flag.option =
        app.add_option("--" + flag.key->entry.options->flag(), flag.value,
                       flag.key->help + " (overrides " + FileKeyOf(flag.key->entry) + ")");
  }
}

bool SettingFlags::Apply(AgentConfig* config, std::string* error) const {
  for (const Flag& flag : flags_) {
    if (flag.option->count() == 0) continue;
    std::string reason;
    const auto command = kapfix::link::MakeSetCommand(flag.key->name, flag.value, &reason);
    if (!command || !ApplySettingsCommand(*command, config, &reason)) {
      if (error) *error = "--" + flag.key->entry.options->flag() + ": " + reason;
      return false;
    }
  }
  return true;
}

}  // namespace kapfix::agent
