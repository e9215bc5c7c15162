// `kapfix-analyze compare`: several strategies on the same swing frames, and whether their
// errors differ (Kruskal–Wallis, as the thesis compared its strategies, Figure 4.26).
#include <cmath>
#include <memory>
#include <sstream>

#include "common/analysis/kruskal_wallis.hpp"
#include "common/evaluation/swing_evaluation.hpp"
#include "common/plot/line_plot.hpp"
#include "common/selection/slice_geometry.hpp"
#include "tools/analyze/command.hpp"
#include "tools/analyze/progress_reporter.hpp"
#include "tools/analyze/swing_setup.hpp"

namespace kapfix::analyze {
namespace {

using plot::PlotSeries;
using plot::RenderLinePlot;

struct CompareArgs {
  SwingArgs swing;
  std::string strategies = "all,h23,h15";
  SliceArgs where;
};

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

nlohmann::json RunCompare(const CompareArgs& args, ReportWriter& report) {
  const std::vector<std::string> names = SplitList(args.strategies);
  if (names.size() < 2) throw std::invalid_argument("--strategies: name at least two strategies");
  std::vector<std::unique_ptr<SearchStrategy>> strategies;
  for (const auto& name : names) strategies.push_back(MakeStrategy(name));
  SwingEvaluationOptions options;
  options.sampling = MakeSampling(args.swing);
  options.search = MakeSearchOptions(args.swing);
  const SwingRecording recording = RecordSwingWithProgress(args.swing);
  const cv::Rect patch = SlicePatch(recording.planes.front().size(), args.where.slices,
                                    args.where.slice, args.swing.patch);

  ProgressReporter progress("compare");
  nlohmann::json per_strategy = nlohmann::json::array();
  std::vector<std::vector<double>> abs_errors;
  std::vector<PlotSeries> series;
  const cv::Scalar colors[] = {{200, 80, 20},  {40, 160, 40}, {20, 20, 200}, {160, 40, 160},
                               {20, 160, 200}, {120, 120, 0}, {0, 0, 0}};
  for (std::size_t i = 0; i < strategies.size(); ++i) {
    progress.SetStage(names[i]);
    const SwingEvaluation e =
        EvaluateSwing(recording.planes, recording.truth, patch, *strategies[i], options,
                      [&](int done, int total) {
                        progress.Update(static_cast<int>(i) * total + done,
                                        static_cast<int>(strategies.size()) * total);
                      });
    std::vector<double> abs;
    for (const double err : e.errors_px) abs.push_back(std::isfinite(err) ? std::abs(err) : 1e9);
    abs_errors.push_back(abs);
    series.push_back({names[i], e.errors_px, colors[i % 7]});
    per_strategy.push_back({{"strategy", names[i]},
                            {"mean_abs_err_px", e.mean_abs_err_px},
                            {"within_2px_pct", e.within_2px_pct},
                            {"gross_fail_pct", e.gross_fail_pct},
                            {"pixels_per_estimate", e.pixels_per_estimate},
                            {"median_us_per_estimate", e.median_us_per_estimate}});
  }
  const KruskalWallisResult kw = KruskalWallis(abs_errors);
  std::vector<std::string> header;
  for (const auto& name : names) header.push_back(name + "_abs_err_px");
  report.WriteCsv("compare.csv", header, abs_errors);
  report.WritePng("compare.png",
                  RenderLinePlot("errors per strategy", "frame", "error [px]", series));
  return {
      {"image", args.swing.image},          {"frames", static_cast<int>(recording.planes.size())},
      {"slice", args.where.slice},          {"strategies", per_strategy},
      {"kruskal_wallis_h", kw.h_corrected}, {"p_value", kw.p_value},
      {"errors_differ", kw.p_value < 0.05}};
}

}  // namespace

void AddCompareCommand(CLI::App& app, OutputArgs* output, CommandRun* run) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* command = app.add_subcommand(
      "compare", "Compare strategies' absolute errors on one swing (Kruskal-Wallis)");
  AddSwingOptions(command, &args->swing);
  AddOutputOptions(command, output);
  command->add_option("--strategies", args->strategies, "Comma-separated strategy names")
      ->capture_default_str();
  AddSliceOptions(command, &args->where);
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunCompare(*args, report); }; });
}

}  // namespace kapfix::analyze
