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

// The field `name` of `type` a member of C++ type `cpp_type` can be copied to and from;
// nullptr with `error` set ("<path>: <reason>") when there is none.
const FieldDescriptor* FindField(const google::protobuf::Descriptor& type, std::string_view name,
                                 std::string_view cpp_type, std::string* error) {
  const FieldDescriptor* field = type.FindFieldByName(std::string(name));
  const std::string path = type.full_name() + "." + std::string(name);
  if (field == nullptr) {
    *error = path + ": no such field, but the options struct lists it";
  } else if (field->is_repeated()) {
    *error = path + ": a list, not one setting";
  } else {
    const FieldDescriptor::CppType t = field->cpp_type();
    const bool fits =
        (cpp_type == "double" && (t == FieldDescriptor::CPPTYPE_FLOAT ||
                                  t == FieldDescriptor::CPPTYPE_DOUBLE || IsWhole(t))) ||
        (cpp_type == "int" && IsWhole(t)) ||
        (cpp_type == "bool" && t == FieldDescriptor::CPPTYPE_BOOL) ||
        (cpp_type == "string" && t == FieldDescriptor::CPPTYPE_STRING) ||
        (cpp_type == "enum" && t == FieldDescriptor::CPPTYPE_ENUM);
    if (fits) return field;
    *error = path + ": a " + field->cpp_type_name() + " cannot be copied into a " +
             std::string(cpp_type) + " member";
  }
  return nullptr;
}

}  // namespace

std::string SettingsFieldCopy::Path(std::string_view name) const {
  return settings_.GetDescriptor()->full_name() + "." + std::string(name);
}

const FieldDescriptor* SettingsFieldCopy::Find(std::string_view name, std::string_view cpp_type) {
  if (!error_.empty()) return nullptr;
  return FindField(*settings_.GetDescriptor(), name, cpp_type, &error_);
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

std::string SettingsFieldWrite::Path(std::string_view name) const {
  return settings_.GetDescriptor()->full_name() + "." + std::string(name);
}

const FieldDescriptor* SettingsFieldWrite::Find(std::string_view name, std::string_view cpp_type) {
  if (!error_.empty()) return nullptr;
  return FindField(*settings_.GetDescriptor(), name, cpp_type, &error_);
}

std::string SettingsFieldWrite::WordOf(const google::protobuf::EnumValueDescriptor& value) {
  return kapfix::v1::SettingWord(value);
}

void SettingsFieldWrite::operator()(std::string_view name, const double& value) {
  const FieldDescriptor* field = Find(name, "double");
  if (field == nullptr) return;
  const auto& r = *settings_.GetReflection();
  switch (field->cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
      r.SetFloat(&settings_, field, static_cast<float>(value));
      break;
    case FieldDescriptor::CPPTYPE_DOUBLE:
      r.SetDouble(&settings_, field, value);
      break;
    case FieldDescriptor::CPPTYPE_INT32:
      r.SetInt32(&settings_, field, static_cast<std::int32_t>(value));
      break;
    default:
      r.SetUInt32(&settings_, field, static_cast<std::uint32_t>(value));
      break;
  }
}

void SettingsFieldWrite::operator()(std::string_view name, const int& value) {
  const FieldDescriptor* field = Find(name, "int");
  if (field == nullptr) return;
  const auto& r = *settings_.GetReflection();
  if (field->cpp_type() == FieldDescriptor::CPPTYPE_INT32) {
    r.SetInt32(&settings_, field, value);
  } else if (value < 0) {
    error_ = Path(name) + " = " + std::to_string(value) + ": must be ≥ 0";
  } else {
    r.SetUInt32(&settings_, field, static_cast<std::uint32_t>(value));
  }
}

void SettingsFieldWrite::operator()(std::string_view name, const bool& value) {
  if (const FieldDescriptor* field = Find(name, "bool")) {
    settings_.GetReflection()->SetBool(&settings_, field, value);
  }
}

void SettingsFieldWrite::operator()(std::string_view name, const std::string& value) {
  if (const FieldDescriptor* field = Find(name, "string")) {
    settings_.GetReflection()->SetString(&settings_, field, value);
  }
}

}  // namespace kapfix::agent
