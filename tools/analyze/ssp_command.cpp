// `kapfix-analyze ssp`: the Slice Selection Process (SPEC §2.6) on a simulated free swing, and
// with --validate, how well each slice score predicts fixation failures on that image.
#include <cmath>
#include <memory>

#include "common/analysis/spearman.hpp"
#include "common/evaluation/swing_evaluation.hpp"
#include "common/plot/line_plot.hpp"
#include "common/selection/slice_selection.hpp"
#include "tools/analyze/command.hpp"
#include "tools/analyze/progress_reporter.hpp"
#include "tools/analyze/swing_setup.hpp"

namespace kapfix::analyze {
namespace {

using plot::PlotSeries;
using plot::RenderSmallMultiples;

struct SspArgs {
  SwingArgs swing;
  std::string strategy = "pyr";
  int slices = 9;
  std::string score = "dc";
  double hysteresis_px = 1.5;
  int deadline_frames = 0;
  double deadline_seconds = 0.0;
  bool validate = false;
};

// Each slice score as a column, in slice order.
struct ScoreColumns {
  explicit ScoreColumns(const std::vector<SliceScore>& slices) {
    for (const SliceScore& s : slices) {
      index.push_back(s.index);
      dc.push_back(s.dc);
      dc_hysteresis.push_back(s.dc_hysteresis);
      fft.push_back(s.fft);
      single_shot.push_back(s.single_shot);
    }
  }
  std::vector<double> index;
  std::vector<double> dc;
  std::vector<double> dc_hysteresis;
  std::vector<double> fft;
  std::vector<double> single_shot;
};

nlohmann::json RunSsp(const SspArgs& args, ReportWriter& report) {
  const auto strategy = MakeStrategy(args.strategy);
  const auto score = ParseSliceScoreKind(args.score);
  if (!score) {
    throw std::invalid_argument("--score: expected dc, dc-hyst, fft or single-shot, got '" +
                                args.score + "'");
  }
  SliceSelectionOptions options;
  options.slice_count = args.slices;
  options.patch_size = args.swing.patch;
  options.sampling = MakeSampling(args.swing);
  options.search = MakeSearchOptions(args.swing);
  options.hysteresis_px = args.hysteresis_px;
  options.score = *score;
  options.deadline_frames = args.deadline_frames;
  options.deadline_seconds = args.deadline_seconds;
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);

  const SwingRecording recording = RecordSwingWithProgress(args.swing);
  ProgressReporter progress("ssp");
  const SliceSelection selection =
      SelectSlice(recording.planes, *strategy, options,
                  [&](int done, int total) { progress.Update(done, total); });

  nlohmann::json slices = nlohmann::json::array();
  std::vector<PlotSeries> graphs;
  std::vector<std::vector<double>> graph_columns;
  std::vector<std::string> graph_header;
  for (const SliceScore& s : selection.slices) {
    slices.push_back({{"index", s.index},
                      {"patch", {s.patch.x, s.patch.y, s.patch.width, s.patch.height}},
                      {"dc", s.dc},
                      {"dc_hysteresis", s.dc_hysteresis},
                      {"fft", s.fft},
                      {"single_shot", s.single_shot}});
    const bool best = s.index == selection.best_slice;
    graphs.push_back({"slice " + std::to_string(s.index) + "  DC " + std::to_string(s.dc) +
                          (best ? "  (best)" : ""),
                      s.graph.samples, best ? cv::Scalar(40, 160, 40) : cv::Scalar(200, 80, 20)});
    graph_columns.push_back(s.graph.samples);
    graph_header.push_back("slice" + std::to_string(s.index) + "_px");
  }
  nlohmann::json summary = {{"image", args.swing.image},
                            {"strategy", args.strategy},
                            {"score", ToString(*score)},
                            {"frames_used", selection.frames_used},
                            {"deadline_hit", selection.deadline_hit},
                            {"scene_upscale", recording.upscale_factor},
                            {"slices", slices},
                            {"ranking", selection.ranking},
                            {"best_slice", selection.best_slice}};

  const ScoreColumns columns(selection.slices);
  std::vector<double> gross;
  if (args.validate) {
    // Fixation on each slice's stored reference through the same swing, against the truth.
    SwingEvaluationOptions evaluation;
    evaluation.sampling = options.sampling;
    evaluation.search = options.search;
    ProgressReporter validate_progress("ssp validation");
    const int count = static_cast<int>(selection.slices.size());
    for (int i = 0; i < count; ++i) {
      const SliceScore& s = selection.slices[i];
      validate_progress.SetStage("slice " + std::to_string(s.index));
      const SwingEvaluation e = EvaluateSwing(
          recording.planes, recording.truth, s.patch, *strategy, evaluation,
          [&](int done, int total) { validate_progress.Update(i * total + done, count * total); });
      summary["slices"][i]["gross_fail_pct"] = e.gross_fail_pct;
      summary["slices"][i]["mean_abs_err_px"] = e.mean_abs_err_px;
      gross.push_back(e.gross_fail_pct);
    }
    // A good score correlates positively with failures for DC and FFT (fewer is better) and
    // negatively for single-shot (higher is better). Undefined (null) when every slice failed
    // equally often.
    auto rho = [&](const std::vector<double>& values) -> nlohmann::json {
      try {
        const double r = SpearmanCorrelation(values, gross);
        return std::isfinite(r) ? nlohmann::json(r) : nlohmann::json(nullptr);
      } catch (const std::invalid_argument&) {
        return nullptr;  // a constant sequence has no rank correlation
      }
    };
    summary["spearman"] = {{"dc", rho(columns.dc)},
                           {"dc-hyst", rho(columns.dc_hysteresis)},
                           {"fft", rho(columns.fft)},
                           {"single-shot", rho(columns.single_shot)}};
  }

  std::vector<std::string> header = {"slice", "dc", "dc_hysteresis", "fft", "single_shot"};
  std::vector<std::vector<double>> table = {columns.index, columns.dc, columns.dc_hysteresis,
                                            columns.fft, columns.single_shot};
  if (!gross.empty()) {
    header.emplace_back("gross_fail_pct");
    table.push_back(gross);
  }
  report.WriteCsv("slices.csv", header, table);
  report.WriteCsv("graphs.csv", graph_header, graph_columns);
  report.WritePng("slices.png", RenderSmallMultiples("displacement graph per slice [px]", graphs));
  return summary;
}

}  // namespace

void AddSspCommand(CLI::App& app, OutputArgs* output, CommandRun* run) {
  auto args = std::make_shared<SspArgs>();
  CLI::App* command =
      app.add_subcommand("ssp", "Slice Selection Process on a simulated free swing (SPEC §2.6)");
  AddSwingOptions(command, &args->swing);
  AddOutputOptions(command, output);
  command->add_option("--strategy", args->strategy, "Search strategy fixation will use")
      ->capture_default_str();
  command->add_option("--slices", args->slices, "Number of horizontal slices")
      ->capture_default_str()
      ->check(CLI::Range(1, 99));
  command->add_option("--score", args->score, "Ranking score: dc, dc-hyst, fft or single-shot")
      ->capture_default_str();
  command->add_option("--hysteresis", args->hysteresis_px, "Hysteresis of dc-hyst [px]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  command
      ->add_option("--deadline-frames", args->deadline_frames,
                   "Stop after this many frames (0 = all)")
      ->capture_default_str();
  command
      ->add_option("--deadline-seconds", args->deadline_seconds,
                   "Stop after this many seconds (0 = no limit)")
      ->capture_default_str();
  command->add_flag("--validate", args->validate,
                    "Also fixate every slice and correlate each score with its failure rate");
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunSsp(*args, report); }; });
}

}  // namespace kapfix::analyze
