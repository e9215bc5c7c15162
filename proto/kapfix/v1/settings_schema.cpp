#include "kapfix/v1/settings_schema.hpp"

#include <google/protobuf/text_format.h>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <memory>

#include "kapfix/v1/command.pb.h"

namespace kapfix::v1 {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumValueDescriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// Shortest text that reads back as the same value: "0.1", "nan", "-inf", "12"; a double that
// is exactly a float (every value a float field carries) as that float, so 1e-45 reads 1e-45.
std::string Num(double value) {
  std::array<char, 64> buffer{};
  const auto as_float = static_cast<float>(value);
  const bool is_float = !std::isfinite(value) || static_cast<double>(as_float) == value;
  const auto result = is_float
                          ? std::to_chars(buffer.data(), buffer.data() + buffer.size(), as_float)
                          : std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

bool IsNumber(const FieldDescriptor& field) {
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
    case FieldDescriptor::CPPTYPE_DOUBLE:
    case FieldDescriptor::CPPTYPE_INT32:
    case FieldDescriptor::CPPTYPE_INT64:
    case FieldDescriptor::CPPTYPE_UINT32:
    case FieldDescriptor::CPPTYPE_UINT64:
      return true;
    default:
      return false;
  }
}

double NumberOf(const Message& message, const FieldDescriptor& field) {
  const Reflection& r = *message.GetReflection();
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
      return r.GetFloat(message, &field);
    case FieldDescriptor::CPPTYPE_DOUBLE:
      return r.GetDouble(message, &field);
    case FieldDescriptor::CPPTYPE_INT32:
      return r.GetInt32(message, &field);
    case FieldDescriptor::CPPTYPE_INT64:
      return static_cast<double>(r.GetInt64(message, &field));
    case FieldDescriptor::CPPTYPE_UINT32:
      return r.GetUInt32(message, &field);
    case FieldDescriptor::CPPTYPE_UINT64:
      return static_cast<double>(r.GetUInt64(message, &field));
    default:
      return 0;
  }
}

// proto3 enums are open: any integer parses, so an unknown value must be refused.
std::string CheckEnum(std::string_view name, int value,
                      const google::protobuf::EnumDescriptor& type) {
  if (value == 0 || type.FindValueByNumber(value) != nullptr) return {};
  std::string known;
  for (int i = 0; i < type.value_count(); ++i) {
    if (type.value(i)->number() == 0) continue;
    if (!known.empty()) known += ", ";
    known += type.value(i)->name();
  }
  return std::string(name) + " = " + std::to_string(value) + ": unknown value, must be one of " +
         known;
}

}  // namespace

const SettingOptions* SettingOf(const FieldDescriptor& field) {
  if (!field.options().HasExtension(setting)) return nullptr;
  return &field.options().GetExtension(setting);
}

const FieldDescriptor* SettingField(const Descriptor& message, std::string_view name) {
  const FieldDescriptor* field = message.FindFieldByName(std::string(name));
  return field != nullptr && SettingOf(*field) != nullptr ? field : nullptr;
}

std::string RangeText(const SettingOptions& options) {
  std::string text = "[" + Num(options.min()) + ", " + Num(options.max()) + "]";
  if (options.zero_means_off()) text = "0 (off) or " + text;
  if (!options.unit().empty() && options.unit() != "1") text += " " + options.unit();
  return text;
}

bool InRange(double value, const SettingOptions& options) {
  if (options.zero_means_off() && value == 0) return true;
  return std::isfinite(value) && value >= options.min() && value <= options.max();
}

std::string OutOfRangeReason(std::string_view name, double value, const SettingOptions& options) {
  return std::string(name) + " = " + Num(value) + ": must be " +
         (std::isfinite(value) ? "in " : "a finite number in ") + RangeText(options);
}

std::string CheckSetting(const Descriptor& message, std::string_view field_name, double value,
                         std::string_view shown_name) {
  const FieldDescriptor* field = SettingField(message, field_name);
  if (field == nullptr) {
    return std::string(shown_name) + ": " + message.full_name() + "." + std::string(field_name) +
           " is not a setting of the schema (a bug)";
  }
  const SettingOptions& options = *SettingOf(*field);
  return InRange(value, options) ? std::string() : OutOfRangeReason(shown_name, value, options);
}

std::string CheckSettings(const Message& message, std::string_view prefix) {
  const Descriptor& type = *message.GetDescriptor();
  const Reflection& reflection = *message.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor& field = *type.field(i);
    const SettingOptions* options = SettingOf(field);
    if (options == nullptr || field.is_repeated() || !reflection.HasField(message, &field)) {
      continue;
    }
    const std::string name =
        prefix.empty() ? field.name() : std::string(prefix) + "." + field.name();
    if (field.cpp_type() == FieldDescriptor::CPPTYPE_ENUM) {
      std::string reason =
          CheckEnum(name, reflection.GetEnumValue(message, &field), *field.enum_type());
      if (!reason.empty()) return reason;
    } else if (IsNumber(field)) {
      const double value = NumberOf(message, field);
      if (!InRange(value, *options)) return OutOfRangeReason(name, value, *options);
    }
  }
  return {};
}

std::string SettingWord(const EnumValueDescriptor& value) {
  if (value.number() == 0) return {};
  if (value.options().HasExtension(setting_word)) {
    return value.options().GetExtension(setting_word).word();
  }
  // The prefix every value of the enum shares: its zero value's name up to the last '_'
  // (proto3: every enum has one, CONTROLLER_KIND_UNSPECIFIED → "CONTROLLER_KIND_").
  const std::string& zero = value.type()->value(0)->name();
  const std::string prefix = zero.substr(0, zero.rfind('_') + 1);
  std::string word =
      value.name().starts_with(prefix) ? value.name().substr(prefix.size()) : value.name();
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word;
}

const EnumValueDescriptor* ValueOfWord(const google::protobuf::EnumDescriptor& type,
                                       std::string_view word) {
  for (int i = 0; i < type.value_count(); ++i) {
    if (!word.empty() && SettingWord(*type.value(i)) == word) return type.value(i);
  }
  return nullptr;
}

void MergeSettings(const Message& from, Message* into) {
  std::unique_ptr<Message> update(from.New());
  update->CopyFrom(from);
  const Descriptor& type = *from.GetDescriptor();
  const Reflection& reflection = *update->GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor* field = type.field(i);
    if (field->cpp_type() == FieldDescriptor::CPPTYPE_ENUM && !field->is_repeated() &&
        reflection.GetEnumValue(*update, field) == 0) {
      reflection.ClearField(update.get(), field);
    }
  }
  into->MergeFrom(*update);
}

bool SetInitialSettings(Message* message, std::string* error) {
  const Descriptor& type = *message->GetDescriptor();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor& field = *type.field(i);
    const SettingOptions* options = SettingOf(field);
    if (options == nullptr || options->initial().empty()) continue;
    if (!google::protobuf::TextFormat::ParseFieldValueFromString(options->initial(), &field,
                                                                 message)) {
      if (error) {
        *error = field.full_name() + ": initial value \"" + options->initial() + "\" is not a " +
                 field.cpp_type_name() + " in protobuf text format";
      }
      return false;
    }
  }
  return true;
}

const std::vector<SettingEntry>& SettingEntries() {
  static const std::vector<SettingEntry> entries = [] {
    std::vector<SettingEntry> found;
    const Descriptor& command = *Command::descriptor();
    for (int i = 0; i < command.field_count(); ++i) {
      const FieldDescriptor* carrier = command.field(i);
      if (const SettingOptions* own = SettingOf(*carrier)) {
        if (!own->key().empty()) found.push_back({carrier, carrier, own});
        continue;
      }
      if (carrier->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) continue;
      const Descriptor& settings = *carrier->message_type();
      for (int j = 0; j < settings.field_count(); ++j) {
        const SettingOptions* options = SettingOf(*settings.field(j));
        if (options != nullptr && !options->key().empty()) {
          found.push_back({carrier, settings.field(j), options});
        }
      }
    }
    return found;
  }();
  return entries;
}

}  // namespace kapfix::v1
