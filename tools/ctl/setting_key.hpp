#pragma once

// The KEYs of `kapfix-ctl set KEY VALUE`: each names one field of a settings command and
// parses its value. Parsing checks syntax only (a number, a known keyword); ranges are the
// agent's to check (CommandValidator), so that the agent's reason reaches the operator and
// the rules live in one place. "nan" and "inf" therefore parse, and the agent refuses them.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kapfix/v1/command.pb.h"

namespace kapfix::ctl {

struct SettingKey {
  std::string_view name;  // e.g. "p", "video_fps"
  std::string_view help;  // value syntax and unit, e.g. "[1] proportional gain"
  // Writes `value` into `command`; false when the text is not a value of this key's type.
  bool (*apply)(kapfix::v1::Command& command, std::string_view value);
};

// Every key, in the order `kapfix-ctl set --help` lists them.
const std::vector<SettingKey>& SettingKeys();

// The command that sets `key` to `value`; std::nullopt and `error` naming the unknown key or
// the unreadable value otherwise.
std::optional<kapfix::v1::Command> MakeSetCommand(std::string_view key, std::string_view value,
                                                  std::string* error);

// One line per key, for --help.
std::string SettingKeysHelp();

}  // namespace kapfix::ctl
