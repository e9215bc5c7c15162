#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/analyze/report_writer.hpp"

namespace kapfix::analyze {

// What a subcommand leaves behind after parsing: a function that does the work, writes its
// files through the ReportWriter and returns the JSON summary.
using CommandRun = std::function<nlohmann::json(ReportWriter&)>;

// Output flags every subcommand takes.
struct OutputArgs {
  bool json = false;
  std::string out_dir;
};

void AddOutputOptions(CLI::App* command, OutputArgs* output);

// One registration function per subcommand (one file each). Each adds its CLI11 subcommand
// to `app` and, when that subcommand is chosen, stores its work in `*run`.
void AddSurfaceCommand(CLI::App& app, OutputArgs* output, CommandRun* run);
void AddSwingCommand(CLI::App& app, OutputArgs* output, CommandRun* run);
void AddSspCommand(CLI::App& app, OutputArgs* output, CommandRun* run);
void AddPssCommand(CLI::App& app, OutputArgs* output, CommandRun* run);
void AddCompareCommand(CLI::App& app, OutputArgs* output, CommandRun* run);
void AddThesisCommand(CLI::App& app, OutputArgs* output, CommandRun* run);

}  // namespace kapfix::analyze
