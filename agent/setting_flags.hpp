#pragma once

// kapfix-agent's flags that set an operator setting (issue 11): one per setting whose schema
// option names a `flag` (setting_options.proto), with the schema's help and range. Each value
// is applied as the settings command `kapfix-ctl set` would send, so it is parsed, checked and
// refused as everywhere else; a new setting with a flag needs nothing here.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "agent/config/agent_config.hpp"
#include "link/setting_key.hpp"

namespace kapfix::agent {

class SettingFlags {
 public:
  // Declares the flags on `app`; app's parse writes into this object, which must therefore
  // stay where it is.
  explicit SettingFlags(CLI::App& app);
  SettingFlags(const SettingFlags&) = delete;
  SettingFlags& operator=(const SettingFlags&) = delete;

  // The flags given, in the schema's order, over `config`. False with "--FLAG: <reason>" at
  // the first value that is not one of the setting's or that `config` cannot take.
  bool Apply(AgentConfig* config, std::string* error) const;

 private:
  struct Flag {
    const kapfix::link::SettingKey* key;
    CLI::Option* option = nullptr;
    std::string value;  // as typed; read when `option` was given
  };
  std::vector<Flag> flags_;
};

}  // namespace kapfix::agent
