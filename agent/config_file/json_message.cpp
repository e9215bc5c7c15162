#include "agent/config_file/json_message.hpp"

#include <google/protobuf/util/json_util.h>

#include <memory>

namespace kapfix::agent {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;

std::string EnumNames(const google::protobuf::EnumDescriptor& type) {
  std::string names;
  for (int i = 0; i < type.value_count(); ++i) {
    names += (names.empty() ? "" : ", ") + type.value(i)->name();
  }
  return names;
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

}  // namespace

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

std::string ReadJsonMessage(const nlohmann::json& object, const std::string& path,
                            google::protobuf::Message* message) {
  if (std::string reason = CheckJsonMessage(object, *message->GetDescriptor(), path);
      !reason.empty()) {
    return reason;
  }
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const std::unique_ptr<google::protobuf::Message> read(message->New());
  const auto status =
      google::protobuf::util::JsonStringToMessage(object.dump(), read.get(), options);
  if (status.ok()) message->MergeFrom(*read);
  return status.ok() ? "" : path + ": " + std::string(status.message());
}

}  // namespace kapfix::agent
