#include "bench/loop_report.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/temp_dir.hpp"

namespace kapfix::bench {
namespace {

// Two scenes × nominal/realistic × both starts × predictive and P, one seed.
LoopPlan TwoScenePlan() {
  LoopPlan plan;
  plan.frames = 100;
  plan.seeds = 1;
  plan.scenes = {"a.jpg", "b.jpg"};
  const std::vector<LoopWorld> worlds = LoopWorlds();
  plan.worlds = {worlds.front(), worlds.back()};
  plan.controllers = {"predictive", "p"};
  plan.starts = {"first-frame", "ssp"};
  plan.sweep_gains = {1.0};
  plan.sweep_scenes = 1;
  return plan;
}

const std::map<std::string, double> kBestGain = {{"nominal", 1.0}, {"realistic", 1.0}};

// The plan's main flights with made-up figures: RMS 10 × (world + 1) + scene index for P,
// half that for the predictive controller (late: a quarter); silent gross 3 % on
// realistic/ssp's scene b alone; an aim floor of world + scene index + 1.
std::vector<LoopRun> MadeUpRuns(const LoopPlan& plan) {
  std::vector<LoopRun> runs;
  for (const LoopFlight& flight : plan.MainFlights(kBestGain)) {
    LoopRun run;
    run.flight = flight;
    run.world = plan.worlds[flight.world].name;
    const double scene = flight.scene == "a.jpg" ? 0 : 1;
    const double p_rms = 10.0 * static_cast<double>(flight.world + 1) + scene;
    const bool predictive = flight.controller == "predictive";
    run.figures.rms_error_px = predictive ? p_rms / 2 : p_rms;
    run.late_rms_error_px = p_rms / 4;
    run.figures.aim_floor_rms_px = static_cast<double>(flight.world) + scene + 1;
    run.figures.silent_gross_pct =
        predictive && run.world == "realistic" && flight.start == "ssp" && scene == 1 ? 3.0 : 0.0;
    runs.push_back(run);
  }
  return runs;
}

TEST(LoopReportTest, EachRowHasItsMediansOverScenesTheLateOneIncluded) {
  const LoopPlan plan = TwoScenePlan();
  const nlohmann::json summary = LoopReport(plan, kBestGain, MadeUpRuns(plan)).Summary("both");
  const nlohmann::json& row = summary["worlds"]["realistic/ssp"];
  EXPECT_DOUBLE_EQ(row["median_rms_error_px"].get<double>(), (10.0 + 10.5) / 2);
  EXPECT_DOUBLE_EQ(row["median_late_rms_error_px"].get<double>(), (5.0 + 5.25) / 2);
  EXPECT_DOUBLE_EQ(row["median_rms_error_px_p_best"].get<double>(), 20.5);
  EXPECT_DOUBLE_EQ(row["silent_gross_pct"].get<double>(), 3.0);
  EXPECT_EQ(summary["worlds"].size(), 4U);
}

TEST(LoopReportTest, EachRowHasTheMedianAimFloorOfItsFlights) {
  const LoopPlan plan = TwoScenePlan();
  const nlohmann::json summary = LoopReport(plan, kBestGain, MadeUpRuns(plan)).Summary("both");
  EXPECT_DOUBLE_EQ(summary["worlds"]["nominal"]["median_aim_floor_px"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(summary["worlds"]["realistic/ssp"]["median_aim_floor_px"].get<double>(), 2.5);
}

TEST(LoopReportTest, TargetsPerStartNameTheWorldWithTheMostSilentGross) {
  const LoopPlan plan = TwoScenePlan();
  const nlohmann::json summary = LoopReport(plan, kBestGain, MadeUpRuns(plan)).Summary("both");
  const nlohmann::json& ssp = summary["by_start"]["ssp"];
  EXPECT_DOUBLE_EQ(ssp["max_silent_gross_pct"].get<double>(), 3.0);
  EXPECT_EQ(ssp["max_silent_gross_world"], "realistic");
  EXPECT_DOUBLE_EQ(ssp["nominal_median_rms_error_px"].get<double>(), 5.25);
  EXPECT_DOUBLE_EQ(summary["by_start"]["first-frame"]["max_silent_gross_pct"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(ssp["realistic_worst_ratio_to_p_best"].get<double>(), 0.5);
}

// A plan of the moving start alone: its rows are labelled so, and the issue's keys come from
// its realistic row (not left empty for want of a first-frame one).
TEST(LoopReportTest, AMovingStartAloneHasItsOwnRowsAndGivesTheIssuesKeys) {
  LoopPlan plan = TwoScenePlan();
  plan.starts = {"moving"};
  std::vector<LoopRun> runs = MadeUpRuns(plan);
  for (LoopRun& run : runs) run.figures.gross_pct = run.world == "realistic" ? 7.0 : 1.0;
  const nlohmann::json summary = LoopReport(plan, kBestGain, runs).Summary("moving");
  EXPECT_TRUE(summary["worlds"].contains("realistic/moving"));
  EXPECT_TRUE(summary["worlds"].contains("nominal/moving"));
  EXPECT_EQ(summary["worlds"].size(), 2U);
  ASSERT_TRUE(summary["gross_pct"].is_number()) << summary["gross_pct"];
  EXPECT_DOUBLE_EQ(summary["gross_pct"].get<double>(), 7.0);
}

TEST(LoopReportTest, CsvHasALinePerFlightInTheRunsOrder) {
  const LoopPlan plan = TwoScenePlan();
  const std::vector<LoopRun> runs = MadeUpRuns(plan);
  const kapfix::testing::TempDir dir;
  const std::string path = (dir.path() / "loop.csv").string();
  LoopReport(plan, kBestGain, runs).WriteCsv(path);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("scene,world,start,slice,controller,", 0), 0U) << line;
  std::size_t k = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(k, runs.size());
    std::ostringstream expected;
    expected << runs[k].flight.scene << ',' << runs[k].world << ',' << runs[k].flight.start << ",0,"
             << runs[k].flight.controller << ',';
    EXPECT_EQ(line.rfind(expected.str(), 0), 0U) << line;
    ++k;
  }
  EXPECT_EQ(k, runs.size());
}

}  // namespace
}  // namespace kapfix::bench
