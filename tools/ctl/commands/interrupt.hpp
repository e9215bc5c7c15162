#pragma once

// Ctrl-C and SIGTERM end a running subcommand cleanly (files flushed, summary printed).

namespace kapfix::ctl {

// Installs the SIGINT and SIGTERM handlers.
void CatchInterrupts();

// True once SIGINT or SIGTERM arrived.
bool Interrupted();

}  // namespace kapfix::ctl
