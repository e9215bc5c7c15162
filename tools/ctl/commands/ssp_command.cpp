// `kapfix-ctl ssp`: start the Slice Selection Process, optionally following it to its result.
#include <memory>
#include <string>
#include <vector>

#include "kapfix/v1/settings_schema.hpp"
#include "kapfix/v1/slices.pb.h"
#include "link/setting_key.hpp"
#include "link/topic_names.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/inbox.hpp"
#include "tools/ctl/commands/interrupt.hpp"
#include "tools/ctl/message_text.hpp"

namespace kapfix::ctl {
namespace {

// An option of the subcommand made from a SetMode field whose schema option names a flag
// (the deadline: --frames); absent, the agent's default holds.
struct ModeFlag {
  kapfix::v1::SettingEntry entry;
  CLI::Option* option = nullptr;
  std::string value;  // as typed; read when `option` was given
};

struct SspArguments {
  bool wait = false;
  std::vector<ModeFlag> flags;
};

// Every SetMode field with a flag (settings_schema: the option's `flag`).
std::vector<ModeFlag> ModeFlags() {
  std::vector<ModeFlag> flags;
  const auto& set_mode = *kapfix::v1::Command::descriptor()->FindFieldByNumber(
      kapfix::v1::Command::kSetModeFieldNumber);
  const auto& type = *set_mode.message_type();
  for (int i = 0; i < type.field_count(); ++i) {
    const kapfix::v1::SettingOptions* options = kapfix::v1::SettingOf(*type.field(i));
    if (options != nullptr && !options->flag().empty()) {
      flags.push_back({{&set_mode, type.field(i), options}, nullptr, {}});
    }
  }
  return flags;
}

int RunSsp(const LinkArguments& link, const SspArguments& arguments) {
  kapfix::v1::Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  for (const ModeFlag& flag : arguments.flags) {
    if (flag.option->count() == 0) continue;
    // Syntax only: the range is the agent's to check, so its reason reaches the operator.
    if (!kapfix::link::SetSettingFromText(command.mutable_set_mode(), *flag.entry.field,
                                          flag.value)) {
      Error("--" + flag.entry.options->flag() + ": cannot read '" + flag.value +
            "': " + kapfix::link::SettingHelp(flag.entry));
      return kBadArguments;
    }
  }
  if (!arguments.wait) return RunSimple(link, std::move(command));

  Inbox<kapfix::v1::SliceReport> reports;  // before the client, whose handler fills it
  auto client = MakeClient(link);
  client->OnMessage(std::string(kapfix::link::kSlicesTopic),
                    [&](const google::protobuf::Message& message) {
                      reports.Put(static_cast<const kapfix::v1::SliceReport&>(message));
                    });
  client->Start();
  if (!StreamsReady(*client, link)) return LinkDown(*client, link);
  reports.Arm();
  const int code = Send(*client, link, std::move(command));
  if (code != kOk) return code;
  while (!Interrupted()) {
    const auto report = reports.Take(std::chrono::milliseconds(50));
    if (report) {
      PrintLine(SliceReportText(*report));
      if (report->finished()) return kOk;
    } else if (!client->Status().up) {
      return LinkDown(*client, link);
    }
  }
  return kOk;
}

}  // namespace

void AddSspCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto arguments = std::make_shared<SspArguments>();
  auto* ssp = app.add_subcommand("ssp", "start the Slice Selection Process");
  ssp->add_flag("--wait", arguments->wait,
                "follow its progress until it finishes and print the recommended slice");
  arguments->flags = ModeFlags();
  for (ModeFlag& flag : arguments->flags) {
    flag.option =
        ssp->add_option("--" + flag.entry.options->flag(), flag.value,
                        kapfix::link::SettingHelp(flag.entry) + " (default: the agent's)");
  }
  ssp->callback(
      [&link, run, arguments] { *run = [&link, arguments] { return RunSsp(link, *arguments); }; });
}

}  // namespace kapfix::ctl
