// `kapfix-analyze ssp`: the Slice Selection Process (SPEC §2.6) on a simulated free swing, and
// with --validate, how well each slice score predicts closed-loop fixation error: scored on
// one seed, validated on another, one entry per distinct patch, Spearman with its p-value and,
// with --pool, a permutation test pooled over images.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "common/analysis/permutation_test.hpp"
#include "common/analysis/spearman.hpp"
#include "common/evaluation/swing_evaluation.hpp"
#include "common/plot/line_plot.hpp"
#include "common/selection/slice_geometry.hpp"
#include "common/selection/slice_selection.hpp"
#include "tools/analyze/command.hpp"
#include "tools/analyze/progress_reporter.hpp"
#include "tools/analyze/ssp_validation.hpp"
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
  std::uint32_t validation_seed = 0;  // 0 = seed + 1000
  int closed_loop_frames = 300;
  std::string pool;  // further images for the pooled permutation test, comma-separated
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

SliceSelectionOptions MakeSelectionOptions(const SspArgs& args) {
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
  return options;
}

nlohmann::json SpearmanJson(const std::map<std::string, SpearmanResult>& all,
                            const std::string& name) {
  const auto it = all.find(name);
  if (it == all.end()) return nullptr;  // a constant sequence: no ranking to correlate
  return {{"rho", it->second.rho}, {"p_value", it->second.p_value}, {"exact", it->second.exact}};
}

// Before any rendering: the frame must hold the slices and the patch.
void CheckFrameHoldsTheSlices(const SspArgs& args, cv::Size frame) {
  if (frame.height < args.slices || args.swing.patch > std::min(frame.width, frame.height)) {
    throw std::invalid_argument("a " + std::to_string(frame.width) + "x" +
                                std::to_string(frame.height) + " frame cannot hold " +
                                std::to_string(args.slices) + " slices with a " +
                                std::to_string(args.swing.patch) + "-px patch (see --size)");
  }
}

// The selection, scored on one swing, or (--validate) on each image with its closed-loop check.
struct SspRun {
  SliceSelection selection;
  double upscale = 1.0;
  std::vector<SspValidation> validations;  // empty without --validate; the first is --image
};

SspRun SelectOrValidate(const SspArgs& args, const SliceSelectionOptions& options,
                        const SearchStrategy& strategy) {
  SspRun run;
  if (!args.validate) {
    const SwingRecording recording = RecordSwingWithProgress(args.swing);
    run.upscale = recording.upscale_factor;
    ProgressReporter progress("ssp");
    run.selection = SelectSlice(recording.planes, strategy, options,
                                [&](int done, int total) { progress.Update(done, total); });
    return run;
  }
  std::vector<std::string> images = {args.swing.image};
  for (const std::string& extra : SplitCommaList(args.pool)) images.push_back(extra);
  ProgressReporter progress("ssp validation");
  for (std::size_t i = 0; i < images.size(); ++i) {
    SspValidationSetup setup;
    setup.swing = args.swing;
    setup.swing.image = images[i];
    setup.strategy = args.strategy;
    setup.selection = options;
    setup.validation_seed = args.validation_seed;
    setup.closed_loop_frames = args.closed_loop_frames;
    run.validations.push_back(
        ValidateSsp(setup, [&](const std::string& stage, int done, int total) {
          progress.SetStage(images[i] + ": " + stage);
          progress.Update(done, total);
        }));
  }
  run.selection = run.validations.front().selection;
  run.upscale = run.validations.front().upscale;
  return run;
}

// Each slice's displacement graph: a plot and a CSV column.
struct SliceGraphs {
  std::vector<PlotSeries> plots;
  std::vector<std::vector<double>> columns;
  std::vector<std::string> header;
};

// Each slice's scores as JSON; its graph into `graphs`.
nlohmann::json SlicesJson(const SliceSelection& selection, SliceGraphs* graphs) {
  nlohmann::json slices = nlohmann::json::array();
  for (const SliceScore& s : selection.slices) {
    slices.push_back({{"index", s.index},
                      {"patch", {s.patch.x, s.patch.y, s.patch.width, s.patch.height}},
                      {"dc", s.dc},
                      {"dc_hysteresis", s.dc_hysteresis},
                      {"fft", s.fft},
                      {"single_shot", s.single_shot}});
    const bool best = s.index == selection.best_slice;
    graphs->plots.push_back({"slice " + std::to_string(s.index) + "  DC " + std::to_string(s.dc) +
                                 (best ? "  (best)" : ""),
                             s.graph.samples,
                             best ? cv::Scalar(40, 160, 40) : cv::Scalar(200, 80, 20)});
    graphs->columns.push_back(s.graph.samples);
    graphs->header.push_back("slice" + std::to_string(s.index) + "_px");
  }
  return slices;
}

// The closed-loop RMS of a validated slice [px].
double RmsOf(const SspValidation& v, int slice) {
  return v.fixation_rms_px[static_cast<std::size_t>(
      std::find(v.distinct.begin(), v.distinct.end(), slice) - v.distinct.begin())];
}

// Over several images: each score's Spearman ρ pooled by a permutation test.
nlohmann::json PooledJson(const std::vector<SspValidation>& validations, std::uint32_t seed) {
  nlohmann::json pooled;
  for (const char* name : {"dc", "dc-hyst", "fft", "single-shot"}) {
    std::vector<std::vector<double>> scores;
    std::vector<std::vector<double>> outcomes;
    for (const SspValidation& each : validations) {
      scores.push_back(each.predicted_badness.at(name));
      outcomes.push_back(each.fixation_rms_px);
    }
    try {
      const PooledPermutationResult p =
          PooledSpearmanPermutationTest(scores, outcomes, 10000, seed);
      pooled[name] = {{"mean_rho", p.mean_rho},
                      {"p_value", p.p_value},
                      {"images_used", p.groups_used},
                      {"permutations", p.permutations}};
    } catch (const std::invalid_argument&) {
      pooled[name] = nullptr;
    }
  }
  return pooled;
}

// --validate's figures into `summary` (per slice, validation, spearman, pooled); returns each
// slice's fixation RMS [px] (NaN for a slice that shares another's patch).
std::vector<double> AddValidation(const SspArgs& args, const SspRun& run, nlohmann::json& summary) {
  const SspValidation& v = run.validations.front();
  std::vector<double> rms(run.selection.slices.size(), std::nan(""));
  for (std::size_t i = 0; i < v.distinct.size(); ++i) {
    const int index = v.distinct[i];
    rms[static_cast<std::size_t>(index - 1)] = v.fixation_rms_px[i];
    summary["slices"][index - 1]["fixation_rms_px"] = v.fixation_rms_px[i];
  }
  nlohmann::json merged = nlohmann::json::array();
  for (const auto& group : v.groups) {
    if (group.size() > 1) merged.push_back(group);
  }
  summary["validation"] = {
      {"scored_on_seed", args.swing.seed},
      {"validated_on_seed",
       args.validation_seed != 0 ? args.validation_seed : args.swing.seed + 1000},
      {"closed_loop_frames", args.closed_loop_frames},
      {"figure", "closed-loop RMS view error per distinct slice [px]"},
      {"distinct_slices", v.distinct},
      {"merged_slices", merged},
      {"best_slice_rms_px", RmsOf(v, v.best_slice)},
      {"worst_slice_rms_px", RmsOf(v, v.worst_slice)}};
  // Positive ρ: the score's "worse" slices fixate worse, as a good score should.
  nlohmann::json spearman;
  for (const char* name : {"dc", "dc-hyst", "fft", "single-shot"}) {
    spearman[name] = SpearmanJson(v.spearman, name);
  }
  summary["spearman"] = spearman;
  if (run.validations.size() > 1) summary["pooled"] = PooledJson(run.validations, args.swing.seed);
  return rms;
}

nlohmann::json RunSsp(const SspArgs& args, ReportWriter& report) {
  const SliceSelectionOptions options = MakeSelectionOptions(args);
  const auto strategy = MakeStrategy(args.swing, args.strategy);
  const cv::Size frame = MakeSwingOptions(args.swing).camera.frame_size;
  CheckFrameHoldsTheSlices(args, frame);
  const SspRun run = SelectOrValidate(args, options, *strategy);
  const SliceSelection& selection = run.selection;

  SliceGraphs graphs;
  nlohmann::json summary = {{"image", args.swing.image},
                            {"strategy", args.strategy},
                            {"score", ToString(options.score)},
                            {"frames_used", selection.frames_used},
                            {"deadline_hit", selection.deadline_hit},
                            {"scene_upscale", run.upscale},
                            {"slices", SlicesJson(selection, &graphs)},
                            {"ranking", selection.ranking},
                            {"best_slice", selection.best_slice}};
  // Slices that share one patch (a frame shorter than slices × patch) are one candidate:
  // the ranking's centre tie-break then picks the inner one of them. A tall enough frame
  // (--size 300x900 for 9 slices of 100 px) gives every slice, edges included, its own.
  nlohmann::json shared = nlohmann::json::array();
  for (const auto& group : SliceGroups(frame, args.slices, args.swing.patch)) {
    if (group.size() > 1) shared.push_back(group);
  }
  summary["shared_patch_slices"] = shared;

  const ScoreColumns columns(selection.slices);
  std::vector<std::string> header = {"slice", "dc", "dc_hysteresis", "fft", "single_shot"};
  std::vector<std::vector<double>> table = {columns.index, columns.dc, columns.dc_hysteresis,
                                            columns.fft, columns.single_shot};
  if (!run.validations.empty()) {
    header.emplace_back("fixation_rms_px");
    table.push_back(AddValidation(args, run, summary));
  }
  report.WriteCsv("slices.csv", header, table);
  report.WriteCsv("graphs.csv", graphs.header, graphs.columns);
  report.WritePng("slices.png",
                  RenderSmallMultiples("displacement graph per slice [px]", graphs.plots));
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
                    "Fixate every distinct slice in closed loop on another seed and correlate "
                    "each score with its fixation error (Spearman, p-value)");
  command
      ->add_option("--validate-seed", args->validation_seed,
                   "Seed of the validation swing (0 = seed + 1000)")
      ->capture_default_str();
  command
      ->add_option("--closed-loop-frames", args->closed_loop_frames,
                   "Closed-loop frames per slice in --validate")
      ->capture_default_str()
      ->check(CLI::Range(20, 100000));
  command
      ->add_option("--pool", args->pool,
                   "Further images (comma-separated) for a pooled permutation test")
      ->capture_default_str();
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunSsp(*args, report); }; });
}

}  // namespace kapfix::analyze
