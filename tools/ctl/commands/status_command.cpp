// `kapfix-ctl status`: the agent's mode, devices and settings (or its AgentState as JSON).
#include <google/protobuf/util/json_util.h>

#include <iostream>
#include <memory>

#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/message_text.hpp"

namespace kapfix::ctl {
namespace {

int RunStatus(const LinkArguments& link, bool json) {
  auto client = MakeClient(link);
  client->Start();
  kapfix::v1::Command command;
  command.mutable_request_state();
  kapfix::v1::Reply reply;
  const int code = Send(*client, link, std::move(command), &reply);
  if (code != kOk) return code;
  if (json) {
    std::string text;
    google::protobuf::util::JsonPrintOptions options;
    options.add_whitespace = true;
    (void)google::protobuf::util::MessageToJsonString(reply.state(), &text, options);
    std::cout << text;
  } else {
    std::cout << StateText(reply.state());
  }
  std::cout.flush();
  return kOk;
}

}  // namespace

void AddStatusCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto json = std::make_shared<bool>(false);
  auto* status = app.add_subcommand("status", "print the agent's mode and settings");
  status->add_flag("--json", *json, "print the AgentState as JSON");
  status->callback([&link, run, json] { *run = [&link, json] { return RunStatus(link, *json); }; });
}

}  // namespace kapfix::ctl
