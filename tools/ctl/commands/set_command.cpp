// `kapfix-ctl set KEY VALUE`: one setting changed; the keys come from the settings schema.
#include <memory>
#include <string>

#include "link/setting_key.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"

namespace kapfix::ctl {
using kapfix::link::MakeSetCommand;
using kapfix::link::SettingKeysHelp;

namespace {

struct SetArguments {
  std::string key;
  std::string value;
};

int RunSet(const LinkArguments& link, const SetArguments& arguments) {
  std::string error;
  auto command = MakeSetCommand(arguments.key, arguments.value, &error);
  if (!command) {
    Error(error);
    return kBadArguments;
  }
  return RunSimple(link, std::move(*command));
}

}  // namespace

void AddSetCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto arguments = std::make_shared<SetArguments>();
  auto* set = app.add_subcommand("set", "change one setting");
  set->footer(SettingKeysHelp());
  set->add_option("key", arguments->key, "setting to change (listed below)")->required();
  set->add_option("value", arguments->value, "its new value")->required();
  set->callback(
      [&link, run, arguments] { *run = [&link, arguments] { return RunSet(link, *arguments); }; });
}

}  // namespace kapfix::ctl
