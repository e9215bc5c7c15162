// kapfix-analyze as a script would use it: exit codes, one-line errors, JSON keys, files.
// Needs Debian's opencv-doc photos (deploy/setup-debian.sh).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/process.hpp"

namespace {

using kapfix::testing::ProcessOutcome;
using kapfix::testing::RunProcess;

ProcessOutcome RunAnalyze(const std::string& args) {
  const std::filesystem::path err_file =
      std::filesystem::temp_directory_path() / ("kapfix_analyze_err_" + std::to_string(::getpid()));
  ProcessOutcome outcome = RunProcess(std::string(KAPFIX_ANALYZE) + " " + args, err_file);
  std::filesystem::remove(err_file);
  return outcome;
}

std::string Photo(const std::string& name) {
  return std::string(KAPFIX_OPENCV_DATA_DIR) + "/" + name;
}

nlohmann::json ParseJson(const ProcessOutcome& outcome) {
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  return nlohmann::json::parse(outcome.out, nullptr, /*allow_exceptions=*/false);
}

TEST(AnalyzeCliTest, SwingPrintsItsFiguresAsJson) {
  const auto json = ParseJson(
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy h23 --frames 120 --json"));
  ASSERT_TRUE(json.is_object());
  for (const char* key : {"mean_abs_err_px", "within_2px_pct", "gross_fail_pct",
                          "pixels_per_estimate", "median_us_per_estimate"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["frames"], 120);
  // h23 over 10 % of a 100×100 patch: at most 23 + a few refinement positions × 1,000 pixels.
  EXPECT_LE(json["pixels_per_estimate"].get<double>(), 30'000.0);
}

TEST(AnalyzeCliTest, SwingWithPyrHoldsTheAerialViewDespiteTheWobble) {
  const auto json = ParseJson(
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy pyr --frames 120 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_LT(json["mean_abs_err_px"].get<double>(), 1.0);
  EXPECT_GT(json["within_2px_pct"].get<double>(), 97.0);
}

TEST(AnalyzeCliTest, SwingWithoutWobbleIsExactForTheExhaustiveSearch) {
  const auto json = ParseJson(RunAnalyze("swing --image " + Photo("aero1.jpg") +
                                         " --strategy all --jitter 0 --frames 60 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_DOUBLE_EQ(json["gross_fail_pct"].get<double>(), 0.0);
}

TEST(AnalyzeCliTest, SwingWritesCsvAndPlotsToTheOutputFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "kapfix_analyze_swing_out";
  std::filesystem::remove_all(dir);
  const ProcessOutcome outcome =
      RunAnalyze("swing --image " + Photo("aero3.jpg") + " --frames 40 --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "swing.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "swing.png"));
  EXPECT_GT(std::filesystem::file_size(dir / "swing.csv"), 100u);
  std::filesystem::remove_all(dir);
}

TEST(AnalyzeCliTest, UnreadableImageExitsNonZeroWithOneLineNamingIt) {
  const ProcessOutcome outcome = RunAnalyze("swing --image /nonexistent/scene.jpg --json");
  EXPECT_NE(outcome.exit_code, 0);
  EXPECT_TRUE(outcome.out.empty());
  EXPECT_NE(outcome.err.find("/nonexistent/scene.jpg"), std::string::npos) << outcome.err;
  EXPECT_EQ(std::count(outcome.err.begin(), outcome.err.end(), '\n'), 1) << outcome.err;
}

TEST(AnalyzeCliTest, UnknownStrategyExitsNonZeroNamingIt) {
  const ProcessOutcome outcome =
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy h99 --frames 10");
  EXPECT_NE(outcome.exit_code, 0);
  EXPECT_NE(outcome.err.find("h99"), std::string::npos) << outcome.err;
}

TEST(AnalyzeCliTest, BadArgumentsExitNonZeroWithOneLine) {
  const ProcessOutcome outcome = RunAnalyze("swing --frames -3");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_EQ(std::count(outcome.err.begin(), outcome.err.end(), '\n'), 1) << outcome.err;
}

TEST(AnalyzeCliTest, SurfaceReportsSuccessRateAndSampledPixels) {
  const auto json = ParseJson(
      RunAnalyze("surface --image " + Photo("fruits.jpg") + " --sampling random:0.25 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_EQ(json["sampled_pixels"], 2500);  // the thesis's random count (Table 3.2)
  const double success = json["success_pct"].get<double>();
  EXPECT_GT(success, 0.0);
  EXPECT_LE(success, 100.0);
}

TEST(AnalyzeCliTest, SspRecommendsOneOfTheSlices) {
  const auto json =
      ParseJson(RunAnalyze("ssp --image " + Photo("aero1.jpg") + " --frames 80 --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["slices"].size(), 9u);
  const int best = json["best_slice"].get<int>();
  EXPECT_GE(best, 1);
  EXPECT_LE(best, 9);
  for (const auto& slice : json["slices"]) {
    EXPECT_TRUE(slice.contains("dc") && slice.contains("fft") && slice.contains("single_shot"));
  }  // 300-px frame: slices 1–2 and 8–9 share a patch, and the summary says so.
  EXPECT_EQ(json["shared_patch_slices"], nlohmann::json::parse("[[1,2],[8,9]]"));
}

// Independent of the tool's statistics code: average ranks by counting.
std::vector<double> Ranks(const std::vector<double>& v) {
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    double below = 0;
    double equal = 0;
    for (const double w : v) {
      below += w < v[i] ? 1 : 0;
      equal += w == v[i] ? 1 : 0;
    }
    r[i] = below + (equal + 1) / 2;
  }
  return r;
}

// Spearman's ρ as the Pearson correlation of ranks computed here, and its exact two-sided p
// by enumerating all n! orderings of the slice indices (the tool enumerates the distinct
// orderings of the rank multiset instead).
std::pair<double, double> SpearmanByEnumeration(const std::vector<double>& a,
                                                const std::vector<double>& b) {
  const std::vector<double> ra = Ranks(a);
  std::vector<double> rb = Ranks(b);
  auto rho = [&](const std::vector<double>& y) {
    const double n = static_cast<double>(y.size());
    double ma = 0, my = 0;
    for (std::size_t i = 0; i < y.size(); ++i) ma += ra[i] / n, my += y[i] / n;
    double sab = 0, saa = 0, syy = 0;
    for (std::size_t i = 0; i < y.size(); ++i) {
      sab += (ra[i] - ma) * (y[i] - my);
      saa += (ra[i] - ma) * (ra[i] - ma);
      syy += (y[i] - my) * (y[i] - my);
    }
    return sab / std::sqrt(saa * syy);
  };
  const double observed = rho(rb);
  std::vector<int> order(a.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  int hits = 0;
  int total = 0;
  do {
    std::vector<double> y;
    for (const int i : order) y.push_back(rb[static_cast<std::size_t>(i)]);
    ++total;
    hits += std::abs(rho(y)) >= std::abs(observed) - 1e-12 ? 1 : 0;
  } while (std::next_permutation(order.begin(), order.end()));
  return {observed, static_cast<double>(hits) / total};
}

TEST(AnalyzeCliTest, SspValidateMergesSharedPatchesAndGivesSpearmanPValues) {
  const auto json = ParseJson(RunAnalyze("ssp --image " + Photo("building.jpg") +
                                         " --frames 60 --validate --closed-loop-frames 40 --json"));
  ASSERT_TRUE(json.is_object());
  // 300-px frame, 9 slices, 100-px patch: slices 1 and 2 (8 and 9) are one patch.
  EXPECT_EQ(json["validation"]["merged_slices"], nlohmann::json::parse("[[1,2],[8,9]]"));
  const auto distinct = json["validation"]["distinct_slices"].get<std::vector<int>>();
  ASSERT_EQ(distinct.size(), 7U);
  EXPECT_NE(json["validation"]["scored_on_seed"], json["validation"]["validated_on_seed"]);
  std::vector<double> dc;
  std::vector<double> rms;
  for (const int index : distinct) {
    dc.push_back(json["slices"][index - 1]["dc"].get<double>());
    rms.push_back(json["slices"][index - 1]["fixation_rms_px"].get<double>());
  }
  ASSERT_FALSE(json["spearman"]["dc"].is_null());
  const auto [rho, p] = SpearmanByEnumeration(dc, rms);
  EXPECT_NEAR(json["spearman"]["dc"]["rho"].get<double>(), rho, 1e-9);
  EXPECT_NEAR(json["spearman"]["dc"]["p_value"].get<double>(), p, 1e-9);
}

TEST(AnalyzeCliTest, SspValidatePooledOverImagesGivesAPermutationPValue) {
  const auto json =
      ParseJson(RunAnalyze("ssp --image " + Photo("aero1.jpg") + " --pool " + Photo("aero3.jpg") +
                           " --frames 40 --validate --closed-loop-frames 20 --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_TRUE(json.contains("pooled"));
  const auto& dc = json["pooled"]["dc"];
  ASSERT_FALSE(dc.is_null());
  EXPECT_EQ(dc["images_used"], 2);
  // (1 + extreme) / (1 + 10,000): never 0, never above 1.
  EXPECT_GE(dc["p_value"].get<double>(), 1.0 / 10001.0);
  EXPECT_LE(dc["p_value"].get<double>(), 1.0);
}

TEST(AnalyzeCliTest, SspRefusesAPatchTooBigForTheFrameNamingTheSizes) {
  const ProcessOutcome o = RunAnalyze("ssp --image " + Photo("aero1.jpg") + " --patch 400 --json");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("400"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("300"), std::string::npos) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
}

TEST(AnalyzeCliTest, PssPicksOneOfTheCandidateSizes) {
  const auto json = ParseJson(
      RunAnalyze("pss --image " + Photo("aero3.jpg") + " --sizes 50,100 --frames 60 --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["sizes"].size(), 2u);
  const int best = json["best_size"].get<int>();
  EXPECT_TRUE(best == 50 || best == 100);
}

TEST(AnalyzeCliTest, CompareOnFiveSeedsGivesPValuesAnIndependentFormulaAgrees) {
  const auto json = ParseJson(RunAnalyze("compare --image " + Photo("aero3.jpg") +
                                         " --strategies all,h23,h15 --frames 60 --runs 5 --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["strategies"].size(), 3U);
  std::vector<std::vector<double>> runs;
  for (const auto& s : json["strategies"]) {
    runs.push_back(s["mean_abs_err_px_per_run"].get<std::vector<double>>());
    ASSERT_EQ(runs.back().size(), 5U);
  }
  // Friedman by the mean-rank form, 12n/(k(k+1)) Σ(R̄ − (k+1)/2)², ranks within each seed;
  // 2 dof: p = exp(−Q/2). Only without ties within a seed (then no correction applies).
  bool tied = false;
  std::vector<double> mean_rank(3, 0.0);
  for (int r = 0; r < 5; ++r) {
    const std::vector<double> ranks = Ranks({runs[0][r], runs[1][r], runs[2][r]});
    for (int j = 0; j < 3; ++j) mean_rank[j] += ranks[j] / 5;
    tied = tied || runs[0][r] == runs[1][r] || runs[1][r] == runs[2][r] || runs[0][r] == runs[2][r];
  }
  double q = 0;
  for (const double m : mean_rank) q += (m - 2) * (m - 2);
  q *= 12.0 * 5 / (3 * 4);
  if (!tied) {
    EXPECT_NEAR(json["friedman"]["chi_square"].get<double>(), q, 1e-9);
    EXPECT_NEAR(json["friedman"]["p_value"].get<double>(), std::exp(-q / 2), 1e-9);
  }
  // Kruskal–Wallis across the 15 runs, as 12/(N(N+1)) Σ n_j(R̄_j − (N+1)/2)² (no ties).
  std::vector<double> pooled;
  for (const auto& g : runs) pooled.insert(pooled.end(), g.begin(), g.end());
  const std::vector<double> ranks = Ranks(pooled);
  std::vector<double> sorted = pooled;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) {
    double h = 0;
    for (int j = 0; j < 3; ++j) {
      double mean = 0;
      for (int r = 0; r < 5; ++r) mean += ranks[static_cast<std::size_t>(j * 5 + r)] / 5;
      h += 5 * (mean - 8) * (mean - 8);
    }
    h *= 12.0 / (15 * 16);
    EXPECT_NEAR(json["kruskal_wallis"]["p_value"].get<double>(), std::exp(-h / 2), 1e-9);
  }
  // Each strategy after the first: the paired difference with a bootstrap interval around it.
  const auto& versus = json["strategies"][1]["versus"];
  EXPECT_LE(versus["mean_difference_px"]["low"].get<double>(),
            versus["mean_difference_px"]["estimate"].get<double>());
  EXPECT_GE(versus["mean_difference_px"]["high"].get<double>(),
            versus["mean_difference_px"]["estimate"].get<double>());
}

TEST(AnalyzeCliTest, CompareRefusesFewerThanFiveRuns) {
  const ProcessOutcome o = RunAnalyze("compare --image " + Photo("aero3.jpg") + " --runs 3");
  EXPECT_EQ(o.exit_code, 2);
}

TEST(AnalyzeCliTest, LiteralRefusesPyrWithTheReason) {
  const ProcessOutcome o =
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy pyr --literal --frames 20");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("not the thesis"), std::string::npos) << o.err;
}

TEST(AnalyzeCliTest, LiteralRefusesBothAxes) {
  const ProcessOutcome o = RunAnalyze("swing --image " + Photo("aero1.jpg") +
                                      " --strategy h23 --literal --axis both --frames 20");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("--literal"), std::string::npos) << o.err;
}

TEST(AnalyzeCliTest, LiteralAcceptsTheThesisPerChannelRgb) {
  const auto json = ParseJson(RunAnalyze("swing --image " + Photo("aero1.jpg") +
                                         " --strategy h23 --literal --channel rgb --jitter 0 "
                                         "--frames 30 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_EQ(json["frames"], 30);
}

TEST(AnalyzeCliTest, LiteralRefusesTheSumOfChannelsWithTheReason) {
  const ProcessOutcome o = RunAnalyze("swing --image " + Photo("aero1.jpg") +
                                      " --strategy h23 --literal --channel rgb-sum --frames 20");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("rgb-sum"), std::string::npos) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
}

TEST(AnalyzeCliTest, SwingWithoutWobbleIsExactOnEveryChannel) {
  for (const char* channel : {"green", "rgb", "rgb-sum"}) {
    const auto json = ParseJson(RunAnalyze("swing --image " + Photo("aero1.jpg") +
                                           " --strategy all --jitter 0 --frames 60 --json "
                                           "--channel " +
                                           channel));
    ASSERT_TRUE(json.is_object()) << channel;
    EXPECT_DOUBLE_EQ(json["gross_fail_pct"].get<double>(), 0.0) << channel;
  }
}

TEST(AnalyzeCliTest, SurfaceAtThesisPixelCountsSamples2500Random) {
  const auto json = ParseJson(RunAnalyze("surface --image " + Photo("fruits.jpg") +
                                         " --sampling random --thesis-pixels --frame 300 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_EQ(json["sampled_pixels"], 2500);
}

TEST(AnalyzeCliTest, SurfaceRefusesAFrameTooSmallForThePatchNamingSizes) {
  const ProcessOutcome o = RunAnalyze("surface --image " + Photo("fruits.jpg") +
                                      " --sampling static --thesis-pixels --frame 200");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("200"), std::string::npos) << o.err;
}

TEST(AnalyzeCliTest, ThesisWritesEntriesWithThesisOursAndHolds) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("kapfix_thesis_" + std::to_string(::getpid()));
  const auto json =
      ParseJson(RunAnalyze("thesis --only table_3_1,table_4_1,table_4_5 --json --out " +
                           out.string() + " --photos " + KAPFIX_OPENCV_DATA_DIR));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["entries"].size(), 3U);
  for (const auto& e : json["entries"]) {
    EXPECT_TRUE(e.contains("thesis") && e.contains("ours") && e["holds"].is_boolean()) << e;
  }
  // Table 4.1: the thesis's 1.11 from its own data, counted its way; 1.21 without the zeros.
  const auto& calibration = json["entries"][1];
  EXPECT_NEAR(calibration["ours"]["thesis_counting"].get<double>(), 1.11, 0.005);
  EXPECT_NEAR(calibration["ours"]["ratio_median"].get<double>(), 1.21, 0.005);
  EXPECT_TRUE(calibration["holds"].get<bool>());
  // Table 4.5: the literal h23 visits 23 offsets, 230,000 pixels at "all".
  EXPECT_EQ(json["entries"][2]["ours"]["h23"]["visits"], 23);
  EXPECT_EQ(json["entries"][2]["ours"]["h23"]["pixels"], 230000);
  EXPECT_TRUE(std::filesystem::exists(out / "report.md"));
  std::filesystem::remove_all(out);
}

TEST(AnalyzeCliTest, ThesisSlicesEntriesComeFromDistinctSlicesOnTwoSeeds) {
  const auto json =
      ParseJson(RunAnalyze("thesis --only table_5_1,best_vs_worst_p,ssp_validation --ssp-images 2 "
                           "--frames 40 --closed-loop-frames 20 --json --photos " +
                           std::string(KAPFIX_OPENCV_DATA_DIR)));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["entries"].size(), 3U);
  for (const auto& [image, row] : json["entries"][0]["ours"].items()) {
    // Best and worst are different slices, the worst with at least the best's DC.
    EXPECT_NE(row["best_slice"], row["worst_slice"]) << image;
    EXPECT_GE(row["worst_dc"].get<int>(), row["best_dc"].get<int>()) << image;
  }
  EXPECT_EQ(json["entries"][1]["ours"]["images"], 2);
  EXPECT_TRUE(json["entries"][2]["holds"].is_boolean());
}

TEST(AnalyzeCliTest, ThesisRefusesAnUnknownEntry) {
  const ProcessOutcome o = RunAnalyze("thesis --only table_9_9");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.err.find("table_9_9"), std::string::npos) << o.err;
}

}  // namespace
