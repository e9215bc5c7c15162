#pragma once

// The KEYs of `kapfix-ctl set KEY VALUE`: each names one field of a settings command and
// parses its value. Keys, help texts and ranges are the settings schema's
// (kapfix/v1/settings_schema.hpp): a field with a `setting` option that has a key is a key
// here, with nothing to add. Parsing checks syntax only (a number, a known keyword); ranges
// are the agent's to check, so that the agent's reason reaches the operator. "nan" and "inf"
// therefore parse, and the agent refuses them.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::link {

struct SettingKey {
  std::string name;  // e.g. "p", "video_fps"
  // Value syntax, what it does and its range, e.g. "proportional gain: … [0.01, 10]".
  std::string help;
  kapfix::v1::SettingEntry entry;  // where the value goes in a Command
};

// Every key, in the order `kapfix-ctl set --help` lists them.
const std::vector<SettingKey>& SettingKeys();

// The command that sets `key` to `value`; std::nullopt and `error` naming the unknown key or
// the unreadable value otherwise.
std::optional<kapfix::v1::Command> MakeSetCommand(std::string_view key, std::string_view value,
                                                  std::string* error);

// One line per key, for --help.
std::string SettingKeysHelp();

// A setting's help as kapfix-ctl and the flags made from the schema show it: the words of an
// enum, "on | off" or the range with the option's help ("how long … (0 = one swing period),
// 0 (off) or [0.1, 30] s").
std::string SettingHelp(const kapfix::v1::SettingEntry& entry);

// Writes `text` into `field` of `target` (a number, on | off, a string, an enum's setting
// word); false when it is not a value of the field's type. The range is not checked.
bool SetSettingFromText(google::protobuf::Message* target,
                        const google::protobuf::FieldDescriptor& field, std::string_view text);

}  // namespace kapfix::link
