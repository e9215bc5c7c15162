#include "agent/config/options_from_settings.hpp"

#include <google/protobuf/descriptor.h>

#include <cstdint>
#include <limits>

#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

using google::protobuf::FieldDescriptor;

bool IsWhole(FieldDescriptor::CppType type) {
  return type == FieldDescriptor::CPPTYPE_INT32 || type == FieldDescriptor::CPPTYPE_UINT32;
}

}  // namespace

std::string SettingsFieldCopy::Path(std::string_view name) const {
  return settings_.GetDescriptor()->full_name() + "." + std::string(name);
}

const FieldDescriptor* SettingsFieldCopy::Find(std::string_view name, std::string_view cpp_type) {
  if (!error_.empty()) return nullptr;
  const FieldDescriptor* field = settings_.GetDescriptor()->FindFieldByName(std::string(name));
  const std::string path = Path(name);
  if (field == nullptr) {
    error_ = path + ": no such field, but the options struct lists it";
  } else if (field->is_repeated()) {
    error_ = path + ": a list, not one setting";
  } else {
    const FieldDescriptor::CppType type = field->cpp_type();
    const bool fits =
        (cpp_type == "double" && (type == FieldDescriptor::CPPTYPE_FLOAT ||
                                  type == FieldDescriptor::CPPTYPE_DOUBLE || IsWhole(type))) ||
        (cpp_type == "int" && IsWhole(type)) ||
        (cpp_type == "bool" && type == FieldDescriptor::CPPTYPE_BOOL) ||
        (cpp_type == "string" && type == FieldDescriptor::CPPTYPE_STRING) ||
        (cpp_type == "enum" && type == FieldDescriptor::CPPTYPE_ENUM);
    if (fits) return field;
    error_ = path + ": a " + field->cpp_type_name() + " cannot be copied into a " +
             std::string(cpp_type) + " member";
  }
  return nullptr;
}

void SettingsFieldCopy::operator()(std::string_view name, double& value) {
  const FieldDescriptor* field = Find(name, "double");
  if (field == nullptr) return;
  const auto& r = *settings_.GetReflection();
  switch (field->cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
      value = r.GetFloat(settings_, field);
      break;
    case FieldDescriptor::CPPTYPE_DOUBLE:
      value = r.GetDouble(settings_, field);
      break;
    case FieldDescriptor::CPPTYPE_INT32:
      value = r.GetInt32(settings_, field);
      break;
    default:
      value = r.GetUInt32(settings_, field);
      break;
  }
}

void SettingsFieldCopy::operator()(std::string_view name, int& value) {
  const FieldDescriptor* field = Find(name, "int");
  if (field == nullptr) return;
  const auto& r = *settings_.GetReflection();
  if (field->cpp_type() == FieldDescriptor::CPPTYPE_INT32) {
    value = r.GetInt32(settings_, field);
    return;
  }
  const std::uint32_t whole = r.GetUInt32(settings_, field);
  if (whole > static_cast<std::uint32_t>(std::numeric_limits<int>::max())) {
    error_ = field->full_name() + " = " + std::to_string(whole) + ": too large for an int";
    return;
  }
  value = static_cast<int>(whole);
}

std::string SettingsFieldCopy::Word(std::string_view name) {
  const FieldDescriptor* field = Find(name, "enum");
  if (field == nullptr) return "";
  std::string word = kapfix::v1::SettingWord(*settings_.GetReflection()->GetEnum(settings_, field));
  if (word.empty()) error_ = Path(name) + ": not set";
  return word;
}

void SettingsFieldCopy::operator()(std::string_view name, bool& value) {
  if (const FieldDescriptor* field = Find(name, "bool")) {
    value = settings_.GetReflection()->GetBool(settings_, field);
  }
}

void SettingsFieldCopy::operator()(std::string_view name, std::string& value) {
  if (const FieldDescriptor* field = Find(name, "string")) {
    value = settings_.GetReflection()->GetString(settings_, field);
  }
}

}  // namespace kapfix::agent
