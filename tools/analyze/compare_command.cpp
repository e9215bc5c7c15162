// `kapfix-analyze compare`: several strategies flown on the same N seeds (N ≥ 5, as the thesis
// flew 5 runs per condition, Figure 4.26), and whether their per-run errors differ.
//
// The unit of analysis is the run, never the frame: the frames of one swing are paired across
// strategies and autocorrelated in time, so a test over frames counts one swing as hundreds of
// independent observations. Each run (seed) gives one summary per strategy, its mean |error|;
// strategies are compared with Kruskal–Wallis across runs (the thesis's test) and, because
// every strategy flies the same seeds, with Friedman (blocks = seeds) and pairwise Wilcoxon
// signed-rank against the first strategy, with effect sizes and bootstrap intervals over runs.
#include <cmath>
#include <memory>
#include <sstream>

#include "common/analysis/bootstrap.hpp"
#include "common/analysis/friedman.hpp"
#include "common/analysis/kruskal_wallis.hpp"
#include "common/analysis/statistics.hpp"
#include "common/analysis/wilcoxon_signed_rank.hpp"
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
  int runs = 5;
};

nlohmann::json Interval(const ConfidenceInterval& ci) {
  return {{"estimate", ci.estimate}, {"low", ci.low}, {"high", ci.high}};
}

// What the runs gave: per_run[j][r] is strategy j's mean |error| on run r [px]; gross likewise
// [%]; the first run's error curves for the plot.
struct CompareRuns {
  std::vector<std::vector<double>> per_run;
  std::vector<std::vector<double>> gross;
  std::vector<PlotSeries> series;
  int frames = 0;
};

// Flies every strategy on the same `args.runs` seeds.
CompareRuns FlyRuns(const CompareArgs& args, const std::vector<std::string>& names,
                    const std::vector<std::unique_ptr<SearchStrategy>>& strategies) {
  const std::size_t k = strategies.size();
  CompareRuns runs;
  runs.per_run.resize(k);
  runs.gross.resize(k);
  const cv::Scalar colors[] = {{200, 80, 20},  {40, 160, 40}, {20, 20, 200}, {160, 40, 160},
                               {20, 160, 200}, {120, 120, 0}, {0, 0, 0}};
  for (int r = 0; r < args.runs; ++r) {
    SwingArgs run_args = args.swing;
    run_args.seed = args.swing.seed + static_cast<std::uint32_t>(r);
    const SwingRecording recording = RecordSwingWithProgress(run_args);
    runs.frames = static_cast<int>(recording.planes.size());
    SwingEvaluationOptions options;
    options.sampling = MakeSampling(run_args);
    options.search = MakeSearchOptions(run_args);
    options.time_searches = false;
    const cv::Rect patch = SlicePatch(recording.planes.front().size(), args.where.slices,
                                      args.where.slice, args.swing.patch);
    ProgressReporter progress("compare run " + std::to_string(r + 1) + "/" +
                              std::to_string(args.runs));
    for (std::size_t j = 0; j < k; ++j) {
      progress.SetStage(names[j]);
      const SwingEvaluation e = EvaluateSwing(recording.planes, recording.truth, patch,
                                              *strategies[j], options, [&](int done, int total) {
                                                progress.Update(static_cast<int>(j) * total + done,
                                                                static_cast<int>(k) * total);
                                              });
      runs.per_run[j].push_back(e.mean_abs_err_px);
      runs.gross[j].push_back(e.gross_fail_pct);
      if (r == 0) runs.series.push_back({names[j], e.errors_px, colors[j % 7]});
    }
  }
  return runs;
}

// Each strategy's runs, bootstrap interval and Friedman rank; from the second on, the paired
// difference to the first (Wilcoxon signed-rank, by seed).
nlohmann::json PerStrategyJson(const std::vector<std::string>& names, const CompareRuns& runs,
                               const FriedmanResult& friedman, const BootstrapOptions& bootstrap) {
  const auto& per_run = runs.per_run;
  nlohmann::json per_strategy = nlohmann::json::array();
  for (std::size_t j = 0; j < names.size(); ++j) {
    nlohmann::json entry = {{"strategy", names[j]},
                            {"mean_abs_err_px_per_run", per_run[j]},
                            {"gross_fail_pct_per_run", runs.gross[j]},
                            {"mean_abs_err_px", Interval(BootstrapMean(per_run[j], bootstrap))},
                            {"gross_fail_pct", Mean(runs.gross[j])},
                            {"friedman_mean_rank", friedman.mean_ranks[j]}};
    if (j > 0) {
      // Paired by seed: the difference to the first strategy, run by run.
      std::vector<double> diff;
      for (std::size_t r = 0; r < per_run[j].size(); ++r)
        diff.push_back(per_run[j][r] - per_run[0][r]);
      const WilcoxonResult w = WilcoxonSignedRank(per_run[j], per_run[0]);
      entry["versus"] = {{"strategy", names[0]},
                         {"mean_difference_px", Interval(BootstrapMean(diff, bootstrap))},
                         {"wilcoxon_p", w.p_value},
                         {"wilcoxon_exact", w.exact},
                         {"rank_biserial", w.rank_biserial}};
    }
    per_strategy.push_back(entry);
  }
  return per_strategy;
}

nlohmann::json RunCompare(const CompareArgs& args, ReportWriter& report) {
  const std::vector<std::string> names = SplitCommaList(args.strategies);
  if (names.size() < 2) throw std::invalid_argument("--strategies: name at least two strategies");
  std::vector<std::unique_ptr<SearchStrategy>> strategies;
  for (const auto& name : names) strategies.push_back(MakeStrategy(args.swing, name));
  const std::size_t k = strategies.size();
  // Before any rendering: the patch must fit the frame (throws naming both sizes).
  SlicePatch(MakeSwingOptions(args.swing).camera.frame_size, args.where.slices, args.where.slice,
             args.swing.patch);
  const CompareRuns runs = FlyRuns(args, names, strategies);

  BootstrapOptions bootstrap;
  bootstrap.seed = args.swing.seed;
  const KruskalWallisResult kw = KruskalWallis(runs.per_run);
  const auto total_runs = static_cast<double>(k * static_cast<std::size_t>(args.runs));
  const FriedmanResult friedman = Friedman(runs.per_run);

  std::vector<std::string> header;
  for (const auto& name : names) header.push_back(name + "_mean_abs_err_px");
  report.WriteCsv("compare_runs.csv", header, runs.per_run);
  report.WritePng("compare.png", RenderLinePlot("errors per strategy (run 1)", "frame",
                                                "error [px]", runs.series));
  return {{"image", args.swing.image},
          {"frames", runs.frames},
          {"runs", args.runs},
          {"first_seed", args.swing.seed},
          {"slice", args.where.slice},
          {"literal", args.swing.literal},
          {"unit", "run (one seed): mean |error| over its frames [px]"},
          {"strategies", PerStrategyJson(names, runs, friedman, bootstrap)},
          {"kruskal_wallis",
           {{"h", kw.h_corrected},
            {"p_value", kw.p_value},
            // ε² = H / (N − 1): the share of rank variance between strategies.
            {"epsilon_squared", kw.h_corrected / (total_runs - 1.0)}}},
          {"friedman",
           {{"chi_square", friedman.chi_square},
            {"p_value", friedman.p_value},
            {"kendall_w", friedman.kendall_w}}},
          {"p_value", friedman.p_value},
          {"errors_differ", friedman.p_value < 0.05}};
}

}  // namespace

void AddCompareCommand(CLI::App& app, OutputArgs* output, CommandRun* run) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* command = app.add_subcommand(
      "compare",
      "Compare strategies over N seeds: per-run errors, Kruskal-Wallis, Friedman, Wilcoxon");
  AddSwingOptions(command, &args->swing);
  AddOutputOptions(command, output);
  command->add_option("--strategies", args->strategies, "Comma-separated strategy names")
      ->capture_default_str();
  command->add_option("--runs", args->runs, "Runs (seeds seed, seed+1, …) per strategy, ≥ 5")
      ->capture_default_str()
      ->check(CLI::Range(5, 1000));
  AddSliceOptions(command, &args->where);
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunCompare(*args, report); }; });
}

}  // namespace kapfix::analyze
