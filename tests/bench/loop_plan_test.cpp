#include "bench/loop_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace kapfix::bench {
namespace {

LoopPlan SmallPlan() {
  LoopPlan plan;
  plan.frames = 100;
  plan.seeds = 2;
  plan.scenes = {"aero1.jpg", "left01.jpg", "fruits.jpg"};
  const std::vector<LoopWorld> worlds = LoopWorlds();
  plan.worlds = {worlds.front(), worlds.back()};
  plan.controllers = {"predictive", "pid", "p"};
  plan.starts = {"first-frame", "ssp"};
  plan.sweep_gains = {0.5, 1.0};
  plan.sweep_scenes = 2;
  return plan;
}

TEST(LoopWorldsTest, AreTheNominalEachDisturbanceAloneAndTheRealistic) {
  const std::vector<LoopWorld> worlds = LoopWorlds();
  ASSERT_EQ(worlds.size(), 12U);
  EXPECT_EQ(worlds.front().name, "nominal");
  EXPECT_EQ(worlds.front().options.Describe(), "nominal");
  EXPECT_EQ(worlds.back().name, "realistic");
  std::set<std::string> names, descriptions;
  for (const LoopWorld& w : worlds) {
    names.insert(w.name);
    descriptions.insert(w.options.Describe());
  }
  EXPECT_EQ(names.size(), worlds.size());
  EXPECT_EQ(descriptions.size(), worlds.size()) << "two worlds with the same disturbances";
}

TEST(LoopPlanTest, MainFlightsAreEveryWorldStartSceneSeedAndControllerOnce) {
  const LoopPlan plan = SmallPlan();
  const std::vector<LoopFlight> flights = plan.MainFlights({{"nominal", 0.5}, {"realistic", 1.0}});
  ASSERT_EQ(flights.size(), 2U * 2U * 3U * 2U * 3U);
  EXPECT_EQ(plan.MainCount(), flights.size());
  std::set<std::tuple<std::size_t, std::string, std::string, int, std::string>> distinct;
  for (const LoopFlight& f : flights) {
    distinct.insert({f.world, f.start, f.scene, f.seed, f.controller});
    EXPECT_EQ(f.gain, f.world == 0 ? 0.5 : 1.0) << "P and PID fly at their world's best gain";
  }
  EXPECT_EQ(distinct.size(), flights.size());
}

TEST(LoopPlanTest, SweepFliesPAtEachGainOnTheFirstSweepScenesFromTheFirstFrame) {
  const LoopPlan plan = SmallPlan();
  const std::vector<LoopFlight> sweep = plan.SweepFlights();
  ASSERT_EQ(sweep.size(), 2U * 2U * 2U);
  EXPECT_EQ(plan.SweepCount(), sweep.size());
  for (const LoopFlight& f : sweep) {
    EXPECT_EQ(f.controller, "p");
    EXPECT_EQ(f.start, "first-frame");
    EXPECT_EQ(f.seed, 1);
    EXPECT_NE(f.scene, "fruits.jpg") << "only the first 2 scenes";
  }
}

TEST(LoopPlanTest, BestGainIsTheLowestMedianRmsOverTheSweepScenes) {
  const LoopPlan plan = SmallPlan();
  const std::vector<LoopFlight> sweep = plan.SweepFlights();
  // Per world, gain, scene: nominal prefers 1.0 (medians 20 vs 15), realistic 0.5 (8 vs 9).
  const std::vector<double> rms = {10, 30, 5, 25, 8, 8, 9, 9};
  const std::map<std::string, double> best = BestGains(plan, sweep, rms);
  EXPECT_EQ(best.at("nominal"), 1.0);
  EXPECT_EQ(best.at("realistic"), 0.5);
}

TEST(LoopPlanTest, EstimateGrowsWithTheFramesAndShrinksWithJobsUpToTheCores) {
  LoopPlan plan = SmallPlan();
  const double one = plan.EstimatedSeconds(1, 2);
  EXPECT_GT(one, 0);
  EXPECT_DOUBLE_EQ(plan.EstimatedSeconds(2, 2), one / 2);
  EXPECT_DOUBLE_EQ(plan.EstimatedSeconds(8, 2), one / 2) << "more jobs than cores gain nothing";
  plan.frames = 1000;
  EXPECT_GT(plan.EstimatedSeconds(1, 2), 2 * one);
}

TEST(LoopPlanTest, DescribeCountsTheFlightsPerKind) {
  const std::string text = SmallPlan().Describe(2, 2);
  EXPECT_NE(text.find("2 worlds × 2 gains × 2 scenes (seed 1, first-frame) = 8 flights"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("2 worlds × 2 starts × 3 scenes × 2 seeds × 3 controllers = 72 flights"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("80 flights of 100 frames, about"), std::string::npos) << text;
  EXPECT_NE(text.find("at --jobs 2"), std::string::npos) << text;
}

TEST(LoopPlanTest, IsValidRefusesAPlanWithoutPTheBaseline) {
  LoopPlan plan = SmallPlan();
  std::string error;
  EXPECT_TRUE(plan.IsValid(&error)) << error;
  plan.controllers = {"predictive"};
  EXPECT_FALSE(plan.IsValid(&error));
  EXPECT_NE(error.find("baseline"), std::string::npos) << error;
}

TEST(LoopPlanTest, IsValidTakesTheMovingStartAndRefusesAnUnknownOneByName) {
  LoopPlan plan = SmallPlan();
  plan.starts = {"moving"};
  std::string error;
  EXPECT_TRUE(plan.IsValid(&error)) << error;
  plan.starts = {"mid-air"};
  EXPECT_FALSE(plan.IsValid(&error));
  EXPECT_NE(error.find("'mid-air'"), std::string::npos) << error;
}

TEST(LoopPlanTest, IsValidRefusesMoreSweepScenesThanScenes) {
  LoopPlan plan = SmallPlan();
  plan.sweep_scenes = 4;
  std::string error;
  EXPECT_FALSE(plan.IsValid(&error));
  EXPECT_NE(error.find("got 4"), std::string::npos) << error;
}

// An agent's loop unlike EvaluateClosedLoop's defaults in everything a flight keeps.
ClosedLoopOptions AgentLoop() {
  ClosedLoopOptions o;
  o.gains.p = 0.7;
  o.gains.rate_limit_deg_per_s = 90;
  o.gains.dead_band_px = 1.5;
  o.frame_period_s = 1.0 / 30;
  o.platform.pan.rate_limit_deg_per_frame = 4;
  o.world = WorldOptions::Realistic();
  return o;
}

TEST(LoopFlightTest, OptionsCarryTheSeedStartWorldAndGain) {
  const LoopFlight flight{"aero1.jpg", 0, "pid", "ssp", 0.8, 7};
  const ClosedLoopOptions o = flight.Options(AgentLoop(), WorldOptions::Nominal(), 123);
  EXPECT_EQ(o.frames, 123);
  EXPECT_EQ(o.start, ClosedLoopOptions::Start::kAfterSsp);
  EXPECT_EQ(o.controller, "pid");
  EXPECT_EQ(o.gains.p, 0.8);
  EXPECT_GT(o.gains.i, 0);
  EXPECT_EQ(o.platform.kite.seed, 7U);
  EXPECT_EQ(o.platform.camera.seed, 7U);
  EXPECT_EQ(o.world.Describe(), WorldOptions::Nominal().Describe());
}

TEST(LoopFlightTest, AMovingStartFliesTheClosedLoopsMovingStart) {
  const LoopFlight flight{"aero1.jpg", 0, "predictive", "moving", 1.0, 1};
  EXPECT_EQ(flight.Options(AgentLoop(), WorldOptions::Nominal(), 50).start,
            ClosedLoopOptions::Start::kMoving);
}

TEST(LoopFlightTest, ThePredictiveControllerKeepsTheAgentsGains) {
  const LoopFlight flight{"aero1.jpg", 0, "predictive", "first-frame", 0.4, 1};
  EXPECT_EQ(flight.Options(AgentLoop(), WorldOptions::Nominal(), 50).gains.p, 0.7);
}

TEST(LoopFlightTest, EveryControllerFliesTheAgentsRateLimitDeadBandServosAndFrameRate) {
  for (const std::string controller : {"predictive", "pid", "p"}) {
    const ClosedLoopOptions o =
        LoopFlight{"aero1.jpg", 0, controller, "first-frame", 1.2, 1}.Options(
            AgentLoop(), WorldOptions::Nominal(), 50);
    EXPECT_EQ(o.gains.rate_limit_deg_per_s, 90) << controller;
    EXPECT_EQ(o.gains.dead_band_px, 1.5) << controller;
    EXPECT_EQ(o.platform.pan.rate_limit_deg_per_frame, 4) << controller;
    EXPECT_DOUBLE_EQ(o.frame_period_s, 1.0 / 30) << controller;
  }
}

TEST(LoopPlanTest, EstimateGrowsWithTheAgentsFrameArea) {
  LoopPlan plan = SmallPlan();
  plan.agent_loop.platform.camera.frame_size = {320, 240};
  const double quarter = plan.EstimatedSeconds(2, 2);
  plan.agent_loop.platform.camera.frame_size = {640, 480};
  EXPECT_GT(plan.EstimatedSeconds(2, 2), 3.5 * quarter);
}

TEST(LoopPlanTest, IsValidRefusesAnAgentLoopThatIsNot) {
  LoopPlan plan = SmallPlan();
  plan.agent_loop.frame_period_s = 0;
  std::string error;
  EXPECT_FALSE(plan.IsValid(&error));
  EXPECT_NE(error.find("frame period"), std::string::npos) << error;
}

TEST(LoopPlanTest, DescribeNamesTheAgentsRateLimitAndFrameRate) {
  LoopPlan plan = SmallPlan();
  plan.agent_loop = AgentLoop();
  const std::string text = plan.Describe(2, 2);
  EXPECT_NE(text.find("rate_limit_deg_per_s 90"), std::string::npos) << text;
  EXPECT_NE(text.find("30 frames/s"), std::string::npos) << text;
}

}  // namespace
}  // namespace kapfix::bench
