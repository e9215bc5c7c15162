// kapfix-ctl: a headless ground station for scripts and tests (issue 3). One subcommand per
// run; the exit code says what happened (see kExitCodes below and --help). Wiring only: each
// subcommand lives in commands/<name>_command.cpp.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "link/curve_key_file.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/interrupt.hpp"

namespace {

using namespace kapfix::ctl;

constexpr const char* kExitCodes =
    "Exit codes:\n"
    "  0  ok\n"
    "  1  the agent refused the command (its reason is printed on stderr)\n"
    "  2  bad arguments (unknown key, unreadable value, missing folder, bad key file)\n"
    "  3  no answer within --timeout: the link is down, no agent listens, or it refused\n"
    "     this station's CurveZMQ key (the reason is printed when ZeroMQ tells it)\n";

void AddLinkOptions(CLI::App& app, LinkArguments* link) {
  app.add_option("--agent", link->host, "agent host name or address")->capture_default_str();
  app.add_option("--command-port", link->command_port, "agent command port (ROUTER)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535));
  app.add_option("--stream-port", link->stream_port, "agent stream port (PUB)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535));
  app.add_option("--timeout", link->timeout_ms,
                 "[ms] wait this long for a reply, or for any message from the agent")
      ->capture_default_str()
      ->check(CLI::Range(1, 3'600'000));
  app.add_option("--agent-id", link->agent_id,
                 "address only the agent with this id (default: whichever listens)");
  auto* key_option =
      app.add_option("--key", link->key_file,
                     "this station's secret key file (kapfix-keygen NAME writes NAME.key)")
          ->check(CLI::ExistingFile);
  auto* agent_key_option =
      app.add_option("--agent-key", link->agent_key_file,
                     "the agent's public key file (its .pub): with --key, the link uses CurveZMQ")
          ->check(CLI::ExistingFile);
  key_option->needs(agent_key_option);
  agent_key_option->needs(key_option);
}

// Reads the CurveZMQ key files named by --key and --agent-key; false after naming the problem.
bool ReadCurveKeys(LinkArguments* link) {
  if (link->key_file.empty()) return true;
  std::string why;
  const auto station = kapfix::link::ReadSecretKeyFile(link->key_file, &why);
  const auto agent =
      station ? kapfix::link::ReadPublicKeyFile(link->agent_key_file, &why) : std::nullopt;
  if (!agent) {
    Error(why);
    return false;
  }
  link->curve = kapfix::link::CurveClientKeys{*station, *agent};
  return true;
}

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-ctl: command a kapfix-agent and read its streams (a headless station)"};
  app.footer(std::string(kExitCodes));
  app.require_subcommand(1);

  LinkArguments link;
  AddLinkOptions(app, &link);
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
