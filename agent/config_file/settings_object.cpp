#include "agent/config_file/settings_object.hpp"

#include <algorithm>

#include "agent/commands/settings_messages.hpp"
#include "agent/config_file/json_message.hpp"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;

constexpr std::string_view kCommandPrefix = "set_";

// A settings command: a Command field that carries settings with a kapfix-ctl key (the
// schema's list, so set_mode, whose deadlines are no settings of the file, is not one).
bool CarriesSettings(const FieldDescriptor& field) {
  const auto& entries = kapfix::v1::SettingEntries();
  return std::any_of(entries.begin(), entries.end(),
                     [&](const kapfix::v1::SettingEntry& e) { return e.command_field == &field; });
}

// The settings command `key` names ("gains" → Command.set_gains); nullptr if none.
const FieldDescriptor* SettingsCommandField(const std::string& key) {
  const FieldDescriptor* field =
      kapfix::v1::Command::descriptor()->FindFieldByName(std::string(kCommandPrefix) + key);
  return field != nullptr && CarriesSettings(*field) ? field : nullptr;
}

// "gains, search, …": the keys the "settings" object takes.
std::string SettingsKeys() {
  std::string keys;
  const Descriptor* command = kapfix::v1::Command::descriptor();
  for (int i = 0; i < command->field_count(); ++i) {
    const FieldDescriptor& field = *command->field(i);
    if (field.name().rfind(kCommandPrefix, 0) != 0 || !CarriesSettings(field)) continue;
    keys += (keys.empty() ? "" : ", ") + field.name().substr(kCommandPrefix.size());
  }
  return keys;
}

// The settings command `key`: `value` → `command`; empty or the reason.
std::string MakeCommand(const std::string& key, const nlohmann::json& value,
                        kapfix::v1::Command* command) {
  const std::string path = "settings." + key;
  const FieldDescriptor* field = SettingsCommandField(key);
  if (field == nullptr) {
    // The one key that moved into a settings message since the object was introduced.
    const char* moved = key == "photo_interval_s" ? "; the photo interval moved into photo" : "";
    return path + ": unknown key (" + SettingsKeys() + ")" + moved;
  }
  if (std::string reason = CheckJsonValue(value, *field, path); !reason.empty()) return reason;
  const auto* reflection = command->GetReflection();
  if (field->message_type() == nullptr) {
    if (!value.is_number()) return path + ": must be a number, got " + value.dump();
    // A settings command that is itself the setting is a number (none is, today).
    const double number = value.get<double>();
    std::string reason =
        kapfix::v1::CheckSetting(*kapfix::v1::Command::descriptor(), field->name(), number, path);
    if (!reason.empty()) return reason;
    if (field->cpp_type() == FieldDescriptor::CPPTYPE_FLOAT) {
      reflection->SetFloat(command, field, static_cast<float>(number));
    } else if (field->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE) {
      reflection->SetDouble(command, field, number);
    } else {
      return path + ": a setting of this type cannot be read from the file yet";
    }
    return "";
  }
  google::protobuf::Message* message = reflection->MutableMessage(command, field);
  if (std::string reason = ReadJsonMessage(value, path, message); !reason.empty()) return reason;
  return kapfix::v1::CheckSettings(*message, path);
}

}  // namespace

bool ApplySettingsObject(const nlohmann::json& settings, AgentConfig* config, std::string* error) {
  auto fail = [error](const std::string& reason) {
    if (error) *error = reason;
    return false;
  };
  if (!settings.is_object()) return fail("settings: must be an object, got " + settings.dump());
  for (const auto& [key, value] : settings.items()) {
    kapfix::v1::Command command;
    if (std::string reason = MakeCommand(key, value, &command); !reason.empty()) {
      return fail(reason);
    }
    std::string reason;
    if (!ApplySettingsCommand(command, config, &reason)) {
      // A cross-field reason names its field ("search.patch_px: …"); others get the key.
      if (reason.find(": ") == std::string::npos) reason.insert(0, "settings." + key + ": ");
      return fail(reason);
    }
  }
  return true;
}

}  // namespace kapfix::agent
