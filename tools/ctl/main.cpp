// kapfix-ctl: a headless ground station for scripts and tests (issue 3). One subcommand per
// run; the exit code says what happened (see kExitCodes below and --help). Wiring only: each
// subcommand lives in commands/<name>_command.cpp, the flags they share in commands/link_flags.
#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/interrupt.hpp"
#include "tools/ctl/commands/link_flags.hpp"

namespace {

using namespace kapfix::ctl;

constexpr const char* kExitCodes =
    "Exit codes:\n"
    "  0  ok\n"
    "  1  the agent refused the command (its reason is printed on stderr)\n"
    "  2  bad arguments (unknown key, unreadable value, missing folder, bad key file)\n"
    "  3  no answer within --timeout: the link is down, no agent listens, or it refused\n"
    "     this station's CurveZMQ key (the reason is printed when ZeroMQ tells it)\n";

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-ctl: command a kapfix-agent and read its streams (a headless station)"};
  app.footer(std::string(kExitCodes));
  app.require_subcommand(1);

  LinkArguments link;
  AddLinkFlags(app, &link);
  CommandRun run;
  AddStatusCommand(app, link, &run);
  AddWatchCommand(app, link, &run);
  AddSetCommand(app, link, &run);
  AddSspCommand(app, link, &run);
  AddSliceCommand(app, link, &run);
  AddFixateCommand(app, link, &run);
  AddPhotoCommand(app, link, &run);
  AddResyncCommand(app, link, &run);
  AddRecordCommand(app, link, &run);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kOk : kBadArguments;
  }
  if (!ReadCurveKeys(&link)) return kBadArguments;

  CatchInterrupts();
  try {
    if (run) return run();
  } catch (const std::runtime_error& error) {
    // The link client refuses an endpoint ZeroMQ cannot read: a bad --agent.
    Error(error.what());
    return kBadArguments;
  }
  return kBadArguments;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& error) {
    Error(std::string("internal error: ") + error.what());
    return kBadArguments;
  }
}
