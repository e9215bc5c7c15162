// `kapfix-analyze swing`: how one strategy holds a stored reference through the open-loop
// swing of SPEC §3 (servos off), against the simulation's truth.
#include <memory>

#include "common/evaluation/swing_evaluation.hpp"
#include "common/plot/line_plot.hpp"
#include "common/selection/slice_geometry.hpp"
#include "tools/analyze/command.hpp"
#include "tools/analyze/progress_reporter.hpp"
#include "tools/analyze/swing_setup.hpp"

namespace kapfix::analyze {
namespace {

using plot::RenderLinePlot;

struct SwingCommandArgs {
  SwingArgs swing;
  std::string strategy = "h23";
  SliceArgs where;
};

nlohmann::json RunSwing(const SwingCommandArgs& args, ReportWriter& report) {
  const auto strategy = MakeStrategy(args.swing, args.strategy);
  SwingEvaluationOptions options;
  options.sampling = MakeSampling(args.swing);
  options.search = MakeSearchOptions(args.swing);
  const SwingRecording recording = RecordSwingWithProgress(args.swing);
  const cv::Size frame = recording.planes.front().size();
  const cv::Rect patch = SlicePatch(frame, args.where.slices, args.where.slice, args.swing.patch);

  ProgressReporter progress("swing " + args.strategy);
  const SwingEvaluation e =
      EvaluateSwing(recording.planes, recording.truth, patch, *strategy, options,
                    [&](int done, int total) { progress.Update(done, total); });

  const bool along_y = options.search.axis == SearchAxis::kY;
  std::vector<double> frame_index;
  std::vector<double> truth;
  std::vector<double> measured;
  for (std::size_t t = 1; t < recording.truth.size(); ++t) {
    frame_index.push_back(static_cast<double>(t));
    truth.push_back(along_y ? recording.truth[t].y : recording.truth[t].x);
    measured.push_back(truth.back() + e.errors_px[t - 1]);
  }
  report.WriteCsv("swing.csv", {"frame", "true_px", "measured_px", "error_px", "search_us"},
                  {frame_index, truth, measured, e.errors_px, e.search_us});
  report.WritePng("swing.png", RenderLinePlot("open-loop swing, " + args.strategy + ", slice " +
                                                  std::to_string(args.where.slice),
                                              "frame", "displacement [px]",
                                              {{"true", truth, {40, 160, 40}},
                                               {"measured", measured, {200, 80, 20}}}));
  report.WritePng("swing_error.png", RenderLinePlot("error (measured - true)", "frame",
                                                    "error [px]", {{"error", e.errors_px}}));
  return {
      {"image", args.swing.image},
      {"strategy", args.strategy},
      {"sampling", ToString(options.sampling)},
      {"slice", args.where.slice},
      {"slices", args.where.slices},
      {"patch", {patch.x, patch.y, patch.width, patch.height}},
      {"frames", static_cast<int>(recording.planes.size())},
      {"scene_upscale", recording.upscale_factor},
      {"mean_abs_err_px", e.mean_abs_err_px},
      {"within_2px_pct", e.within_2px_pct},
      {"gross_fail_pct", e.gross_fail_pct},
      {"pixels_per_estimate", e.pixels_per_estimate},
      {"median_us_per_estimate", e.median_us_per_estimate},
      {"not_found", e.not_found},
  };
}

}  // namespace

void AddSwingCommand(CLI::App& app, OutputArgs* output, CommandRun* run) {
  auto args = std::make_shared<SwingCommandArgs>();
  CLI::App* command = app.add_subcommand(
      "swing", "Hold a stored reference through the simulated open-loop swing (SPEC §3)");
  AddSwingOptions(command, &args->swing);
  AddOutputOptions(command, output);
  command->add_option("--strategy", args->strategy, "all, h23, h21, h19, h17, h15 or pyr")
      ->capture_default_str();
  AddSliceOptions(command, &args->where);
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunSwing(*args, report); }; });
}

}  // namespace kapfix::analyze
