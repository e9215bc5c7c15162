// `kapfix-analyze pss`: Patch Size Selection (SPEC §2.5) on a simulated free swing.
#include <memory>
#include <sstream>

#include "common/selection/patch_size_selection.hpp"
#include "tools/analyze/command.hpp"
#include "tools/analyze/progress_reporter.hpp"
#include "tools/analyze/swing_setup.hpp"

namespace kapfix::analyze {
namespace {

struct PssArgs {
  SwingArgs swing;
  std::string strategy = "pyr";
  std::vector<int> sizes = {50, 100, 150};
};

nlohmann::json RunPss(const PssArgs& args, ReportWriter& report) {
  const auto strategy = MakeStrategy(args.swing, args.strategy);
  PatchSizeSelectionOptions options;
  options.sizes = args.sizes;
  options.sampling = MakeSampling(args.swing);
  options.search = MakeSearchOptions(args.swing);
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  const SwingRecording recording = RecordSwingWithProgress(args.swing);
  ProgressReporter progress("pss");
  const PatchSizeSelection selection =
      SelectPatchSize(recording.planes, *strategy, options,
                      [&](int done, int total) { progress.Update(done, total); });
  nlohmann::json sizes = nlohmann::json::array();
  std::vector<double> size_column;
  std::vector<double> dc_column;
  std::vector<double> fft_column;
  for (const PatchSizeScore& s : selection.sizes) {
    sizes.push_back({{"size", s.size}, {"dc", s.dc}, {"fft", s.fft}});
    size_column.push_back(s.size);
    dc_column.push_back(s.dc);
    fft_column.push_back(s.fft);
  }
  report.WriteCsv("sizes.csv", {"size", "dc", "fft"}, {size_column, dc_column, fft_column});
  return {{"image", args.swing.image},
          {"strategy", args.strategy},
          {"frames", static_cast<int>(recording.planes.size())},
          {"sizes", sizes},
          {"best_size", selection.best_size}};
}

}  // namespace

void AddPssCommand(CLI::App& app, OutputArgs* output, CommandRun* run) {
  auto args = std::make_shared<PssArgs>();
  CLI::App* command =
      app.add_subcommand("pss", "Patch Size Selection on a simulated free swing (SPEC §2.5)");
  AddSwingOptions(command, &args->swing);
  AddOutputOptions(command, output);
  command->add_option("--strategy", args->strategy, "Search strategy fixation will use")
      ->capture_default_str();
  command->add_option("--sizes", args->sizes, "Candidate patch sides [px], comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunPss(*args, report); }; });
}

}  // namespace kapfix::analyze
