#pragma once

// A JSON value of the configuration file read as a kapfix.v1 message by protobuf's JSON
// mapping, with the file's strictness: protobuf's own errors name neither the field nor the
// line, so the value is checked first and a problem is "<path>.<field>: <reason>", which
// agent_config_file places on its line.

#include <google/protobuf/message.h>

#include <nlohmann/json.hpp>
#include <string>

namespace kapfix::agent {

// Empty when `value` has a JSON type protobuf's mapping reads into `field` (null: unset; a
// message is checked as CheckJsonMessage); else "<path>: <reason>".
std::string CheckJsonValue(const nlohmann::json& value,
                           const google::protobuf::FieldDescriptor& field, const std::string& path);

// `object` into `message` (merged over what it holds): an object whose every key is a field
// of the message (by its name or its JSON name) with a value of its type. Empty, or the first
// problem; `message` may be partly read then.
std::string ReadJsonMessage(const nlohmann::json& object, const std::string& path,
                            google::protobuf::Message* message);

}  // namespace kapfix::agent
