#pragma once

// The link calls every subcommand shares: a client configured from the link arguments, one
// command sent with its outcome as an exit code, and the "link down" verdict.

#include <chrono>
#include <memory>

#include "kapfix/v1/command.pb.h"
#include "link/agent_link_client.hpp"
#include "tools/ctl/commands/command.hpp"

namespace kapfix::ctl {

using Clock = std::chrono::steady_clock;

std::unique_ptr<kapfix::link::AgentLinkClient> MakeClient(const LinkArguments& link);

// Sends one command and reports the outcome as an exit code; `reply` receives an OK reply.
int Send(kapfix::link::AgentLinkClient& client, const LinkArguments& link,
         kapfix::v1::Command command, kapfix::v1::Reply* reply = nullptr);

// A client of its own, one command, "ok" on success.
int RunSimple(const LinkArguments& link, kapfix::v1::Command command);

// True while the agent was heard within --timeout (counting from `since` if never heard).
bool LinkAlive(const kapfix::link::AgentLinkClient& client, const LinkArguments& link,
               Clock::time_point since);

// Names the silent endpoint (and the handshake's refusal if any); returns kNoAnswer.
int LinkDown(const kapfix::link::AgentLinkClient& client, const LinkArguments& link);

// Waits for the stream subscription to be live, so that results published right after the
// command are not lost (ZeroMQ PUB does not keep messages for late subscribers).
bool StreamsReady(kapfix::link::AgentLinkClient& client, const LinkArguments& link);

}  // namespace kapfix::ctl
