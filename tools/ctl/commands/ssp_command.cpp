// `kapfix-ctl ssp`: start the Slice Selection Process, optionally following it to its result.
#include <memory>

#include "kapfix/v1/slices.pb.h"
#include "link/topic_names.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/inbox.hpp"
#include "tools/ctl/commands/interrupt.hpp"
#include "tools/ctl/message_text.hpp"

namespace kapfix::ctl {
namespace {

struct SspArguments {
  bool wait = false;
  unsigned frames = 0;  // [frames] deadline; 0 = the agent's
};

int RunSsp(const LinkArguments& link, const SspArguments& arguments) {
  kapfix::v1::Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  if (arguments.frames > 0) command.mutable_set_mode()->set_deadline_frames(arguments.frames);
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
  ssp->add_option("--frames", arguments->frames, "deadline in frames (default: the agent's)")
      ->check(CLI::PositiveNumber);
  ssp->callback(
      [&link, run, arguments] { *run = [&link, arguments] { return RunSsp(link, *arguments); }; });
}

}  // namespace kapfix::ctl
