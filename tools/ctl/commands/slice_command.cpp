// `kapfix-ctl slice N`: fixate on one of the slices the SSP found.
#include <memory>

#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"

namespace kapfix::ctl {

void AddSliceCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto slice_index = std::make_shared<unsigned>(0);
  auto* slice = app.add_subcommand("slice", "fixate on slice N (1 = top)");
  slice->add_option("N", *slice_index, "slice index")->required();
  slice->callback([&link, run, slice_index] {
    *run = [&link, slice_index] {
      kapfix::v1::Command command;
      command.set_select_slice(*slice_index);
      return RunSimple(link, std::move(command));
    };
  });
}

}  // namespace kapfix::ctl
