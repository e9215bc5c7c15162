#pragma once

// The flags every kapfix-ctl subcommand shares: where the agent listens, how long to wait, and
// the CurveZMQ key files, read once the command line is parsed.

#include <CLI/CLI.hpp>

#include "tools/ctl/commands/command.hpp"

namespace kapfix::ctl {

// Adds --agent, --command-port, --stream-port, --timeout, --agent-id, --key and --agent-key to
// `app`; their values land in `*link` when app parses.
void AddLinkFlags(CLI::App& app, LinkArguments* link);

// Reads the CurveZMQ key files named by --key and --agent-key into link->curve; none named:
// true, nothing read. False after naming the problem on stderr.
bool ReadCurveKeys(LinkArguments* link);

}  // namespace kapfix::ctl
