#include "agent/config/config_reader.hpp"

#include <cmath>
#include <limits>

namespace kapfix::agent {
namespace {

const char* TypeName(const nlohmann::json& value) {
  if (value.is_null()) return "null";
  if (value.is_boolean()) return "a boolean";
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_array()) return "an array";
  return "an object";
}

}  // namespace

ConfigReader::ConfigReader(const nlohmann::json& object, std::string path)
    : object_(object), path_(std::move(path)) {
  if (!object_.is_object()) {
    error_ = (path_.empty() ? std::string("the file") : path_) + ": must be a JSON object, got " +
             TypeName(object_);
  }
}

std::string ConfigReader::FieldPath(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool ConfigReader::Fail(std::string_view key, const std::string& message) {
  if (error_.empty()) error_ = FieldPath(key) + ": " + message;
  return false;
}

bool ConfigReader::WrongType(std::string_view key, const char* expected,
                             const nlohmann::json& value) {
  return Fail(key,
              std::string("must be ") + expected + ", got " + TypeName(value) + " " + value.dump());
}

const nlohmann::json* ConfigReader::Take(std::string_view key) {
  if (!ok()) return nullptr;
  read_.emplace(key);
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

bool ConfigReader::Read(std::string_view key, double* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_number()) return WrongType(key, "a number", *json);
  *value = json->get<double>();
  return true;
}

bool ConfigReader::Read(std::string_view key, std::optional<double>* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (json->is_null()) {
    value->reset();
    return true;
  }
  if (!json->is_number()) return WrongType(key, "a number or null", *json);
  *value = json->get<double>();
  return true;
}

bool ConfigReader::Read(std::string_view key, int* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_number_integer()) return WrongType(key, "an integer", *json);
  if (json->is_number_unsigned() &&
      json->get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    return Fail(key, "integer out of range: " + json->dump());
  }
  return StoreInt(key, json->get<std::int64_t>(), value);
}

bool ConfigReader::StoreInt(std::string_view key, std::int64_t wide, int* value) {
  if (wide < std::numeric_limits<int>::min() || wide > std::numeric_limits<int>::max()) {
    return Fail(key, "integer out of range: " + std::to_string(wide));
  }
  *value = static_cast<int>(wide);
  return true;
}

bool ConfigReader::Read(std::string_view key, std::uint32_t* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_number_integer()) return WrongType(key, "an integer", *json);
  if (json->is_number_unsigned() && json->get<std::uint64_t>() <= 0xFFFFFFFFu) {
    *value = static_cast<std::uint32_t>(json->get<std::uint64_t>());
    return true;
  }
  return Fail(key, "must be an integer 0…4294967295, got " + json->dump());
}

bool ConfigReader::Read(std::string_view key, bool* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_boolean()) return WrongType(key, "true or false", *json);
  *value = json->get<bool>();
  return true;
}

bool ConfigReader::Read(std::string_view key, std::string* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_string()) return WrongType(key, "a string", *json);
  *value = json->get<std::string>();
  return true;
}

bool ConfigReader::ReadInteger(std::string_view key, int* value) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (json->is_number_unsigned()) {
    const auto wide = json->get<std::uint64_t>();
    if (wide > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
      return Fail(key, "integer out of range: " + json->dump());
    }
    return StoreInt(key, static_cast<std::int64_t>(wide), value);
  }
  if (json->is_number_integer()) return StoreInt(key, json->get<std::int64_t>(), value);
  if (!json->is_string()) return WrongType(key, "an integer or a string like \"0x40\"", *json);
  const std::string text = json->get<std::string>();
  std::size_t used = 0;
  long long parsed = 0;
  try {
    parsed = std::stoll(text, &used, 0);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    return Fail(key, "must be an integer such as 64 or \"0x40\", got \"" + text + "\"");
  }
  return StoreInt(key, parsed, value);
}

bool ConfigReader::ReadObject(std::string_view key,
                              const std::function<bool(ConfigReader&)>& read) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  ConfigReader child(*json, FieldPath(key));
  if (child.ok()) read(child);
  if (child.ok()) child.Finish();
  if (!child.ok()) error_ = child.error();
  return ok();
}

bool ConfigReader::ReadObjectArray(
    std::string_view key, const std::function<bool(ConfigReader&, std::size_t index)>& read) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_array()) return WrongType(key, "an array", *json);
  for (std::size_t i = 0; i < json->size() && ok(); ++i) {
    ConfigReader child((*json)[i], FieldPath(key) + "[" + std::to_string(i) + "]");
    if (child.ok()) read(child, i);
    if (child.ok()) child.Finish();
    if (!child.ok()) error_ = child.error();
  }
  return ok();
}

bool ConfigReader::Finish() {
  if (!ok()) return false;
  for (auto it = object_.begin(); it != object_.end(); ++it) {
    if (read_.count(it.key()) == 0) {
      return Fail(it.key(), "unknown key (a typo? see resources/README.md for every key)");
    }
  }
  return true;
}

}  // namespace kapfix::agent
