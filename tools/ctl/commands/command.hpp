#pragma once

// kapfix-ctl's subcommands, one file each; main.cpp only wires them. Each Add*Command adds its
// CLI11 subcommand to `app` and, when that subcommand is chosen, stores its work in `*run`. The
// work reads `link` when it runs, after parsing (main fills in the CurveZMQ keys then).

#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "link/curve_key_file.hpp"

namespace kapfix::ctl {

enum Exit : int { kOk = 0, kRefused = 1, kBadArguments = 2, kNoAnswer = 3 };

struct LinkArguments {
  std::string host = "localhost";
  int command_port = 5555;
  int stream_port = 5556;
  int timeout_ms = 3000;
  std::string agent_id;
  std::string key_file;        // this station's secret key file (kapfix-keygen)
  std::string agent_key_file;  // the agent's public key file
  std::optional<kapfix::link::CurveClientKeys> curve;  // read from the two files

  std::chrono::milliseconds timeout() const { return std::chrono::milliseconds(timeout_ms); }
  std::string CommandEndpoint() const {
    return "tcp://" + host + ":" + std::to_string(command_port);
  }
  std::string StreamEndpoint() const { return "tcp://" + host + ":" + std::to_string(stream_port); }
};

// What the chosen subcommand does; returns the exit code.
using CommandRun = std::function<int()>;

void AddStatusCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddWatchCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddSetCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddSspCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddSliceCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddFixateCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddPhotoCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddResyncCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);
void AddRecordCommand(CLI::App& app, const LinkArguments& link, CommandRun* run);

}  // namespace kapfix::ctl
