#pragma once

// The settings schema (issue 11): each operator-settable field's range, unit, help text and
// kapfix-ctl key are its `setting` option (setting_options.proto), read here through the
// descriptors. The agent's config check, its command validator, kapfix-ctl, the station's
// editors and the fuzzers' invariants all ask these functions, so a range is written once
// and an out-of-range value gets the same reason from every one of them.

#include <google/protobuf/descriptor.h>
#include <google/protobuf/generated_enum_reflection.h>
#include <google/protobuf/message.h>

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "kapfix/v1/setting_options.pb.h"

namespace kapfix::v1 {

// The field's setting option; nullptr when it has none (not a setting).
const SettingOptions* SettingOf(const google::protobuf::FieldDescriptor& field);

// The field `name` of `message` that is a setting; nullptr when there is none such.
const google::protobuf::FieldDescriptor* SettingField(const google::protobuf::Descriptor& message,
                                                      std::string_view name);

// "[0.01, 10]", "[1, 1000] deg/s", "0 (off) or [0.5, 86400] s": the range as every reason and
// help text shows it (a unit "1", a pure ratio, is not shown).
std::string RangeText(const SettingOptions& options);

// Finite and in [min, max], or 0 where 0 means off.
bool InRange(double value, const SettingOptions& options);

// The one out-of-range reason: "<name> = <value>: must be in <range>", or "must be a finite
// number in <range>" for NaN and infinities. `value` is shown in the shortest text that
// reads back as the same float.
std::string OutOfRangeReason(std::string_view name, double value, const SettingOptions& options);

// Empty when `value` is in the range of setting `field_name` of `message`; else the reason
// naming `shown_name`. A field that is no setting is a bug: its reason says so.
std::string CheckSetting(const google::protobuf::Descriptor& message, std::string_view field_name,
                         double value, std::string_view shown_name);

// Every field present in `message` that is a setting: numbers in range, enums a known value
// (or *_UNSPECIFIED, "unchanged"). The first problem, named "<prefix>.<field>"; empty when
// there is none. Nested messages are not walked.
std::string CheckSettings(const google::protobuf::Message& message, std::string_view prefix);

// The word an operator types for an enum value: its setting_word option, or the value's name
// without the enum's prefix in lower case (CONTROLLER_KIND_PID → "pid"). Empty for
// *_UNSPECIFIED.
std::string SettingWord(const google::protobuf::EnumValueDescriptor& value);

// SettingWord of a generated enum's value (kapfix::v1::CONTROLLER_KIND_PID → "pid"); empty for
// *_UNSPECIFIED or a number the enum does not have.
template <typename Enum>
std::string WordOf(Enum value) {
  const auto* described =
      google::protobuf::GetEnumDescriptor<Enum>()->FindValueByNumber(static_cast<int>(value));
  return described == nullptr ? std::string() : SettingWord(*described);
}

// The enum value whose SettingWord is `word` ("pid" → CONTROLLER_KIND_PID); nullptr for none.
const google::protobuf::EnumValueDescriptor* ValueOfWord(
    const google::protobuf::EnumDescriptor& type, std::string_view word);

// A settings command's partial update of the settings held: protobuf's merge (a field present
// replaces, an absent one keeps; an empty string keeps), except that an enum at *_UNSPECIFIED
// keeps the held value even where the field has presence (settings.proto: "unchanged").
// `from` and `into` are the same message type.
void MergeSettings(const google::protobuf::Message& from, google::protobuf::Message* into);

// Sets every setting field of `message` whose option has an `initial` value to it: the agent's
// defaults, written once next to the field's range. False with "<message>.<field>: ..." when
// an initial value does not parse as the field's type (a bug in the schema).
bool SetInitialSettings(google::protobuf::Message* message, std::string* error);

// `Settings` with its initial values; throws std::logic_error for a schema that has a bad one
// (the schema's test catches that first).
template <typename Settings>
Settings InitialSettings() {
  Settings settings;
  std::string error;
  if (!SetInitialSettings(&settings, &error)) throw std::logic_error(error);
  return settings;
}

// A setting as kapfix-ctl and the station list it: the command field that carries it
// ("set_gains") and its field within that message (the command field itself when it is the
// setting, a scalar command; none is, today).
struct SettingEntry {
  const google::protobuf::FieldDescriptor* command_field;
  const google::protobuf::FieldDescriptor* field;  // the setting; == command_field if scalar
  const SettingOptions* options;
};

// Every setting with a kapfix-ctl key, in the order of Command's fields and then of the
// settings messages' fields.
const std::vector<SettingEntry>& SettingEntries();

}  // namespace kapfix::v1
