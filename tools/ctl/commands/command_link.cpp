#include "tools/ctl/commands/command_link.hpp"

#include <algorithm>
#include <string>

#include "tools/ctl/commands/command_output.hpp"

namespace kapfix::ctl {

using kapfix::link::AgentLinkClient;

std::unique_ptr<AgentLinkClient> MakeClient(const LinkArguments& link) {
  kapfix::link::AgentLinkClientOptions options;
  options.command_endpoint = link.CommandEndpoint();
  options.stream_endpoint = link.StreamEndpoint();
  options.agent_id = link.agent_id;
  options.curve = link.curve;
  // Link loss is declared after --timeout of silence. Our own heartbeats, echoed by the
  // agent, come three times per timeout so that a short --timeout does not mistake the
  // agent's slower stream heartbeats (1 s) for a lost link.
  options.link_timeout = link.timeout();
  options.heartbeat_interval = std::clamp<std::chrono::milliseconds>(
      link.timeout() / 3, std::chrono::milliseconds(10), options.heartbeat_interval);
  return std::make_unique<AgentLinkClient>(options);
}

int Send(AgentLinkClient& client, const LinkArguments& link, kapfix::v1::Command command,
         kapfix::v1::Reply* reply) {
  const auto answer = client.Request(std::move(command), link.timeout());
  if (!answer) {
    const std::string refused = client.Status().handshake_failure;
    Error("no answer from " + link.CommandEndpoint() + " within " +
          std::to_string(link.timeout_ms) + " ms (" +
          (refused.empty() ? std::string("link down or no agent") : refused) + ")");
    return kNoAnswer;
  }
  if (!answer->ok()) {
    Error("agent refused: " + answer->reason() + " [" +
          kapfix::v1::ErrorCode_Name(answer->error()) + "]");
    return kRefused;
  }
  if (reply != nullptr) *reply = *answer;
  return kOk;
}

int RunSimple(const LinkArguments& link, kapfix::v1::Command command) {
  auto client = MakeClient(link);
  client->Start();
  const int code = Send(*client, link, std::move(command));
  if (code == kOk) PrintLine("ok");
  return code;
}

bool LinkAlive(const AgentLinkClient& client, const LinkArguments& link, Clock::time_point since) {
  if (client.Status().up) return true;
  return Clock::now() - since < link.timeout() && client.Status().last_heard_us == 0;
}

int LinkDown(const AgentLinkClient& client, const LinkArguments& link) {
  const std::string refused = client.Status().handshake_failure;
  Error("no message from the agent at " + link.StreamEndpoint() + " within " +
        std::to_string(link.timeout_ms) + " ms (" +
        (refused.empty() ? std::string("link down or no agent") : refused) + ")");
  return kNoAnswer;
}

bool StreamsReady(AgentLinkClient& client, const LinkArguments& link) {
  return client.WaitForStreams(link.timeout());
}

}  // namespace kapfix::ctl
