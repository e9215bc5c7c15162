#include "agent/config_file/settings_object.hpp"

#include <google/protobuf/util/json_util.h>

#include <algorithm>

#include "agent/commands/settings_messages.hpp"
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

std::string EnumNames(const google::protobuf::EnumDescriptor& type) {
  std::string names;
  for (int i = 0; i < type.value_count(); ++i) {
    names += (names.empty() ? "" : ", ") + type.value(i)->name();
  }
  return names;
}

std::string CheckJsonMessage(const nlohmann::json& object, const Descriptor& message,
                             const std::string& path);

// Empty when `value` has a JSON type protobuf's mapping reads into `field` (null: unset);
// else "<path>: <reason>". protobuf's own error names neither the field nor the line.
std::string CheckJsonValue(const nlohmann::json& value, const FieldDescriptor& field,
                           const std::string& path) {
  if (value.is_null()) return "";
  auto wrong = [&](const char* expected) {
    return path + ": must be " + expected + ", got " + value.dump();
  };
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_MESSAGE:
      return CheckJsonMessage(value, *field.message_type(), path);
    case FieldDescriptor::CPPTYPE_ENUM:
      if (value.is_string() &&
          field.enum_type()->FindValueByName(value.get<std::string>()) != nullptr) {
        return "";
      }
      return path + ": unknown value " + value.dump() + " (" + EnumNames(*field.enum_type()) + ")";
    case FieldDescriptor::CPPTYPE_STRING:
      return value.is_string() ? "" : wrong("a string");
    case FieldDescriptor::CPPTYPE_BOOL:
      return value.is_boolean() ? "" : wrong("true or false");
    case FieldDescriptor::CPPTYPE_FLOAT:
    case FieldDescriptor::CPPTYPE_DOUBLE:
      return value.is_number() ? "" : wrong("a number");
    case FieldDescriptor::CPPTYPE_UINT32:
    case FieldDescriptor::CPPTYPE_UINT64:
      return value.is_number_unsigned() ? "" : wrong("a whole number ≥ 0");
    case FieldDescriptor::CPPTYPE_INT32:
    case FieldDescriptor::CPPTYPE_INT64:
      return value.is_number_integer() ? "" : wrong("a whole number");
  }
  return wrong("a value of its type");
}

// Unknown fields are refused (a typo must not fall back to a default silently).
std::string CheckJsonMessage(const nlohmann::json& object, const Descriptor& message,
                             const std::string& path) {
  if (!object.is_object()) return path + ": must be an object, got " + object.dump();
  for (const auto& [key, value] : object.items()) {
    const FieldDescriptor* field = message.FindFieldByName(key);
    if (field == nullptr) field = message.FindFieldByCamelcaseName(key);
    std::string field_path = path;
    field_path.append(".").append(key);
    if (field == nullptr) {
      return field_path.append(": unknown field of ")
          .append(message.full_name())
          .append(" (a typo? see resources/README.md)");
    }
    if (field->is_repeated()) return field_path.append(": lists are not settings");
    if (std::string reason = CheckJsonValue(value, *field, field_path); !reason.empty()) {
      return reason;
    }
  }
  return "";
}

// The settings command `key`: `value` → `command`; empty or the reason.
std::string MakeCommand(const std::string& key, const nlohmann::json& value,
                        kapfix::v1::Command* command) {
  const std::string path = "settings." + key;
  const FieldDescriptor* field = SettingsCommandField(key);
  if (field == nullptr) return path + ": unknown key (" + SettingsKeys() + ")";
  if (std::string reason = CheckJsonValue(value, *field, path); !reason.empty()) return reason;
  const auto* reflection = command->GetReflection();
  if (field->message_type() == nullptr) {
    if (!value.is_number()) return path + ": must be a number, got " + value.dump();
    // The schema's scalar settings commands are numbers (set_photo_interval_s).
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
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(value.dump(), message, options);
  if (!status.ok()) return path + ": " + std::string(status.message());
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
