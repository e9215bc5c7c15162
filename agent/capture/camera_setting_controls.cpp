#include "agent/capture/camera_setting_controls.hpp"

#include <fmt/format.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <algorithm>
#include <optional>

#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

using google::protobuf::FieldDescriptor;

// The field's value as a number; nullopt for a type a camera control cannot take.
std::optional<double> NumberOf(const google::protobuf::Message& message,
                               const FieldDescriptor& field) {
  const google::protobuf::Reflection& reflection = *message.GetReflection();
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
      return reflection.GetFloat(message, &field);
    case FieldDescriptor::CPPTYPE_DOUBLE:
      return reflection.GetDouble(message, &field);
    case FieldDescriptor::CPPTYPE_BOOL:
      return reflection.GetBool(message, &field) ? 1.0 : 0.0;
    case FieldDescriptor::CPPTYPE_INT32:
      return reflection.GetInt32(message, &field);
    case FieldDescriptor::CPPTYPE_UINT32:
      return reflection.GetUInt32(message, &field);
    case FieldDescriptor::CPPTYPE_ENUM:
      return reflection.GetEnumValue(message, &field);
    default:
      return std::nullopt;
  }
}

// "gain_db = 6 dB", "auto_exposure = true": the setting as the config file names it.
std::string Shown(const FieldDescriptor& field, double value) {
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_BOOL) {
    return field.name() + " = " + (value != 0 ? "true" : "false");
  }
  const kapfix::v1::SettingOptions* option = kapfix::v1::SettingOf(field);
  const bool unit = option != nullptr && !option->unit().empty() && option->unit() != "1";
  return fmt::format("{} = {:g}{}", field.name(), value, unit ? " " + option->unit() : "");
}

}  // namespace

CameraSettingControls& CameraSettingControls::Add(int field_number, Control control) {
  controls_.push_back({field_number, std::move(control)});
  return *this;
}

bool CameraSettingControls::Apply(const kapfix::v1::CameraSettings& settings,
                                  const std::string& camera, std::string* error) const {
  std::vector<const FieldDescriptor*> fields;
  settings.GetReflection()->ListFields(settings, &fields);  // the set ones, in field order
  std::string refused;
  for (const FieldDescriptor* field : fields) {
    const std::optional<double> value = NumberOf(settings, *field);
    const auto control =
        std::find_if(controls_.begin(), controls_.end(),
                     [field](const Entry& entry) { return entry.field_number == field->number(); });
    std::string reason;
    if (!value) {  // a field type no camera control takes (a bug in the schema)
      refused += (refused.empty() ? "" : "; ") + field->name() + ": not a number";
      continue;
    }
    if (control == controls_.end()) {
      reason = "this camera has no such control";
    } else if (control->control(*value, &reason)) {
      continue;
    }
    refused += (refused.empty() ? "" : "; ") + Shown(*field, *value) + ": " + reason;
  }
  if (refused.empty()) return true;
  if (error) *error = camera + ": " + refused;
  return false;
}

}  // namespace kapfix::agent
