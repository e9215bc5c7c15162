// kapfix-analyze: offline studies of the vision core on photos (SPEC §2, §3). Wiring only:
// each subcommand lives in its own *_command.cpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "tools/analyze/command.hpp"

namespace kapfix::analyze {

void AddOutputOptions(CLI::App* command, OutputArgs* output) {
  command->add_flag("--json", output->json, "Print the summary as JSON on stdout");
  command->add_option("--out", output->out_dir, "Folder for CSV tables and PNG plots");
}

namespace {

// Without --json: one "key: value" line per scalar, arrays and objects as compact JSON.
void PrintHuman(const nlohmann::json& summary) {
  for (const auto& [key, value] : summary.items()) {
    std::cout << key << ": " << (value.is_string() ? value.get<std::string>() : value.dump())
              << '\n';
  }
}

}  // namespace
}  // namespace kapfix::analyze

namespace {

int Main(int argc, char** argv) {
  using namespace kapfix::analyze;
  CLI::App app{"kapfix-analyze: offline analysis of the kapfix vision core on photos"};
  app.require_subcommand(1);
  OutputArgs output;
  CommandRun run;
  AddSurfaceCommand(app, &output, &run);
  AddSwingCommand(app, &output, &run);
  AddSspCommand(app, &output, &run);
  AddPssCommand(app, &output, &run);
  AddCompareCommand(app, &output, &run);
  AddThesisCommand(app, &output, &run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "kapfix-analyze: " << e.what() << " (see --help)\n";
    return 2;
  }
  try {
    ReportWriter report(output.out_dir);
    const nlohmann::json summary = run(report);
    if (output.json) {
      std::cout << summary.dump(2) << '\n';
    } else {
      PrintHuman(summary);
    }
    if (report.enabled()) {
      std::cerr << "wrote " << report.written().size() << " files to " << output.out_dir << '\n';
    }
  } catch (const std::exception& e) {
    std::cerr << "kapfix-analyze: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "kapfix-analyze: " << e.what() << '\n';
  } catch (...) {
    std::cerr << "kapfix-analyze: unexpected error\n";
  }
  return 1;
}
