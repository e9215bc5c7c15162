#include "link/setting_key.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>

namespace kapfix::link {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using kapfix::v1::Command;

template <typename T>
std::optional<T> ParseNumber(std::string_view text) {
  T value{};
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

std::optional<bool> ParseBool(std::string_view text) {
  if (text == "on" || text == "true" || text == "yes" || text == "1") return true;
  if (text == "off" || text == "false" || text == "no" || text == "0") return false;
  return std::nullopt;
}

// "p | pid | predictive": the words of an enum's values.
std::string Words(const google::protobuf::EnumDescriptor& type) {
  std::string words;
  for (int i = 0; i < type.value_count(); ++i) {
    const std::string word = kapfix::v1::SettingWord(*type.value(i));
    if (!word.empty()) words += (words.empty() ? "" : " | ") + word;
  }
  return words;
}

}  // namespace

std::string SettingHelp(const kapfix::v1::SettingEntry& entry) {
  const FieldDescriptor& field = *entry.field;
  const kapfix::v1::SettingOptions& o = *entry.options;
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_ENUM:
      return Words(*field.enum_type()) + ": " + o.help();
    case FieldDescriptor::CPPTYPE_BOOL:
      return "on | off: " + o.help();
    case FieldDescriptor::CPPTYPE_STRING:
      return o.help();
    default:
      return o.help() + ", " + kapfix::v1::RangeText(o);
  }
}

bool SetSettingFromText(Message* target_message, const FieldDescriptor& field,
                        std::string_view text) {
  Message& target = *target_message;
  const auto& r = *target.GetReflection();
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT: {
      const auto value = ParseNumber<float>(text);
      if (value) r.SetFloat(&target, &field, *value);
      return value.has_value();
    }
    case FieldDescriptor::CPPTYPE_UINT32: {
      const auto value = ParseNumber<std::uint32_t>(text);
      if (value) r.SetUInt32(&target, &field, *value);
      return value.has_value();
    }
    case FieldDescriptor::CPPTYPE_BOOL: {
      const auto value = ParseBool(text);
      if (value) r.SetBool(&target, &field, *value);
      return value.has_value();
    }
    case FieldDescriptor::CPPTYPE_STRING:
      if (text.empty()) return false;
      r.SetString(&target, &field, std::string(text));
      return true;
    case FieldDescriptor::CPPTYPE_ENUM: {
      const auto& type = *field.enum_type();
      for (int i = 0; i < type.value_count(); ++i) {
        if (!text.empty() && kapfix::v1::SettingWord(*type.value(i)) == text) {
          r.SetEnumValue(&target, &field, type.value(i)->number());
          return true;
        }
      }
      return false;
    }
    default:
      return false;  // no setting has another type (SettingsSchemaTest keeps it so)
  }
}

namespace {

bool Apply(const kapfix::v1::SettingEntry& entry, Command& command, std::string_view text) {
  if (entry.field == entry.command_field) return SetSettingFromText(&command, *entry.field, text);
  Message* settings = command.GetReflection()->MutableMessage(&command, entry.command_field);
  return SetSettingFromText(settings, *entry.field, text);
}

}  // namespace

const std::vector<SettingKey>& SettingKeys() {
  static const std::vector<SettingKey> keys = [] {
    std::vector<SettingKey> found;
    for (const kapfix::v1::SettingEntry& entry : kapfix::v1::SettingEntries()) {
      found.push_back({entry.options->key(), SettingHelp(entry), entry});
    }
    return found;
  }();
  return keys;
}

std::optional<Command> MakeSetCommand(std::string_view key, std::string_view value,
                                      std::string* error) {
  for (const SettingKey& setting : SettingKeys()) {
    if (setting.name != key) continue;
    Command command;
    if (Apply(setting.entry, command, value)) return command;
    if (error != nullptr) {
      *error = "cannot read '" + std::string(value) + "' as a value of " + std::string(key) + ": " +
               setting.help;
    }
    return std::nullopt;
  }
  if (error != nullptr) {
    *error = "unknown key '" + std::string(key) + "' (see kapfix-ctl set --help)";
  }
  return std::nullopt;
}

std::string SettingKeysHelp() {
  std::string text = "Keys:\n";
  for (const SettingKey& setting : SettingKeys()) {
    std::string name = setting.name;
    name.resize(std::max<std::size_t>(name.size() + 1, 17), ' ');
    text += "  " + name + setting.help + "\n";
  }
  return text;
}

}  // namespace kapfix::link
