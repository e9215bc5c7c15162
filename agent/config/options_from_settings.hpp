#pragma once

// Copies a kapfix.v1 settings message into one of common/'s options structs by field name
// (issue 11: a setting is named in its field, its use and nowhere in between). The options
// struct lists its operator-set fields once, next to their declaration:
//   template <typename Visitor> void VisitFields(Visitor&& visit) { visit("p", p); ... }
// and each name is a field of the settings message. common/ stays free of protobuf: the
// descriptors are read here.

#include <google/protobuf/message.h>

#include <stdexcept>
#include <string>
#include <string_view>

namespace kapfix::agent {

// The visitor VisitFields is called with: reads each named field of `settings`, present or not
// (an absent optional field reads its zero), into the options' member. The first problem — a
// name the message lacks, a type it cannot hold — is kept, and nothing is copied after it.
class SettingsFieldCopy {
 public:
  explicit SettingsFieldCopy(const google::protobuf::Message& settings) : settings_(settings) {}

  void operator()(std::string_view name, double& value);
  void operator()(std::string_view name, int& value);
  void operator()(std::string_view name, bool& value);
  void operator()(std::string_view name, std::string& value);
  // An enum of the options' own, by the word an operator types for the setting's value
  // (kapfix::v1::SettingWord): `parse` turns it into the options' enum, an std::optional.
  template <typename Enum, typename Parse>
  void operator()(std::string_view name, Enum& value, Parse parse) {
    const std::string word = Word(name);
    if (!error_.empty()) return;
    const auto parsed = parse(word);
    if (!parsed) {
      error_ = Path(name) + " = " + word + ": the options' enum has no such value";
      return;
    }
    value = *parsed;
  }

  // Empty when every visited name was copied; else "<message>.<name>: <reason>".
  const std::string& error() const { return error_; }

 private:
  const google::protobuf::FieldDescriptor* Find(std::string_view name, std::string_view cpp_type);
  // The setting word of enum field `name`; "" with error_ set when it is none or unset.
  std::string Word(std::string_view name);
  std::string Path(std::string_view name) const;

  const google::protobuf::Message& settings_;
  std::string error_;
};

// The other way: writes each member VisitFields names into that field of `settings` (an enum
// of the options' own goes by the setting word its `parse` turns into the member's value).
// Used where the agent holds a setting in a struct of its own (SearchConfig, LensProfile): the
// state, and a command's merge, see it as the message. The first problem is kept.
class SettingsFieldWrite {
 public:
  explicit SettingsFieldWrite(google::protobuf::Message* settings) : settings_(*settings) {}

  void operator()(std::string_view name, const double& value);
  void operator()(std::string_view name, const int& value);
  void operator()(std::string_view name, const bool& value);
  void operator()(std::string_view name, const std::string& value);
  template <typename Enum, typename Parse>
  void operator()(std::string_view name, const Enum& value, Parse parse) {
    const google::protobuf::FieldDescriptor* field = Find(name, "enum");
    if (field == nullptr) return;
    const google::protobuf::EnumDescriptor& type = *field->enum_type();
    for (int i = 0; i < type.value_count(); ++i) {
      const auto parsed = parse(WordOf(*type.value(i)));
      if (parsed && *parsed == value) {
        settings_.GetReflection()->SetEnumValue(&settings_, field, type.value(i)->number());
        return;
      }
    }
    error_ = Path(name) + ": the options' value has no setting word";
  }

  const std::string& error() const { return error_; }

 private:
  const google::protobuf::FieldDescriptor* Find(std::string_view name, std::string_view cpp_type);
  static std::string WordOf(const google::protobuf::EnumValueDescriptor& value);
  std::string Path(std::string_view name) const;

  google::protobuf::Message& settings_;
  std::string error_;
};

// `options` with the fields it visits copied from `settings`. False with the reason (a bug in
// the pairing, which the tests catch) and `options` partly copied.
template <typename Options>
bool CopySettings(const google::protobuf::Message& settings, Options* options, std::string* error) {
  SettingsFieldCopy copy(settings);
  options->VisitFields(copy);
  if (!copy.error().empty() && error) *error = copy.error();
  return copy.error().empty();
}

// `base` (the options' defaults for what is no setting) with the settings copied in; throws
// std::logic_error where CopySettings fails.
template <typename Options>
Options OptionsFromSettings(const google::protobuf::Message& settings, Options base = {}) {
  std::string error;
  if (!CopySettings(settings, &base, &error)) throw std::logic_error(error);
  return base;
}

// `Settings` (a kapfix.v1 settings message) with every field `options` visits set from it;
// throws std::logic_error for a pairing the message cannot hold (the tests catch it).
template <typename Settings, typename Options>
Settings SettingsFromOptions(Options options) {
  Settings settings;
  SettingsFieldWrite write(&settings);
  options.VisitFields(write);
  if (!write.error().empty()) throw std::logic_error(write.error());
  return settings;
}

// As SettingsFromOptions, but a value the message cannot hold (a negative count) is a reason,
// not a bug: false with "<message>.<field> = <value>: …" and `settings` partly written.
template <typename Options>
bool WriteSettings(Options options, google::protobuf::Message* settings, std::string* error) {
  SettingsFieldWrite write(settings);
  options.VisitFields(write);
  if (!write.error().empty() && error) *error = write.error();
  return write.error().empty();
}

}  // namespace kapfix::agent
