#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>

namespace kapfix::agent {

// Reads one JSON object of the configuration strictly: every value's type is checked, absent
// keys leave the default in place, and Finish() reports any key nobody read — a typo must not
// silently fall back to a default. Errors name the field by its dotted path
// ("servo.pan.max_deg"). After the first error every call does nothing and returns false.
class ConfigReader {
 public:
  // `path` is the object's own path ("" for the root). An `object` that is not a JSON object
  // is an error.
  ConfigReader(const nlohmann::json& object, std::string path);

  bool Read(std::string_view key, double* value);
  bool Read(std::string_view key, int* value);
  bool Read(std::string_view key, std::uint32_t* value);
  bool Read(std::string_view key, bool* value);
  bool Read(std::string_view key, std::string* value);
  // null or absent → std::nullopt.
  bool Read(std::string_view key, std::optional<double>* value);
  // An integer, or a string in C notation ("0x40").
  bool ReadInteger(std::string_view key, int* value);
  // A string turned into a value by `parse`, which returns false and a reason when it cannot.
  template <typename T>
  bool ReadParsed(
      std::string_view key, T* value,
      const std::type_identity_t<std::function<bool(const std::string&, T*, std::string*)>>& parse);
  // A nested object, read by `read` with its own reader (whose Finish is called here).
  bool ReadObject(std::string_view key, const std::function<bool(ConfigReader&)>& read);
  // An array of objects, each read by `read` with a reader whose path is "key[i]".
  bool ReadObjectArray(std::string_view key,
                       const std::function<bool(ConfigReader&, std::size_t index)>& read);

  // Marks `key` read without reading it: another reader owns it.
  void Skip(std::string_view key) { read_.emplace(key); }

  // Whether the object has `key` (does not mark it read).
  bool Has(std::string_view key) const { return object_.is_object() && object_.contains(key); }

  // Unknown keys are an error naming the first one.
  bool Finish();

  // Marks the reader failed with "<path.key>: <message>".
  bool Fail(std::string_view key, const std::string& message);

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  std::string FieldPath(std::string_view key) const;

 private:
  // The value under `key` (and marks it read), or nullptr when absent or after an error.
  const nlohmann::json* Take(std::string_view key);
  bool WrongType(std::string_view key, const char* expected, const nlohmann::json& value);
  bool StoreInt(std::string_view key, std::int64_t wide, int* value);

  const nlohmann::json& object_;
  std::string path_;
  std::set<std::string, std::less<>> read_;
  std::string error_;
};

template <typename T>
bool ConfigReader::ReadParsed(
    std::string_view key, T* value,
    const std::type_identity_t<std::function<bool(const std::string&, T*, std::string*)>>& parse) {
  const nlohmann::json* json = Take(key);
  if (json == nullptr) return ok();
  if (!json->is_string()) return WrongType(key, "a string", *json);
  std::string reason;
  if (!parse(json->get<std::string>(), value, &reason)) return Fail(key, reason);
  return true;
}

}  // namespace kapfix::agent
