// `kapfix-ctl fixate`: store a new reference and hold the view.
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"

namespace kapfix::ctl {

void AddFixateCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto* fixate = app.add_subcommand("fixate", "store a new reference and hold the view");
  fixate->callback([&link, run] {
    *run = [&link] {
      kapfix::v1::Command command;
      command.mutable_set_mode()->set_mode(kapfix::v1::MODE_FIXATE);
      return RunSimple(link, std::move(command));
    };
  });
}

}  // namespace kapfix::ctl
