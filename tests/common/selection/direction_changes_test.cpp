#include "common/selection/direction_changes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "tests/common/selection/swing_frames.hpp"

namespace kapfix {
namespace {

// [px] Exact frame-to-frame motion of x(t) = A·sin(2πt/T) over `frames` frames (frames − 1
// samples): a sampled cosine.
std::vector<double> SmoothSwingGraph(int frames, double amplitude, double period) {
  std::vector<double> graph;
  for (int t = 1; t < frames; ++t) {
    const auto x = [&](int k) { return amplitude * std::sin(2.0 * std::numbers::pi * k / period); };
    graph.push_back(x(t) - x(t - 1));
  }
  return graph;
}

TEST(DirectionChangesTest, CountsEachLocalExtremum) {
  EXPECT_EQ(CountDirectionChanges({0, 1, 2, 1, 0, 1}), 2);
}

TEST(DirectionChangesTest, APlateauBetweenARiseAndAFallIsOneExtremum) {
  EXPECT_EQ(CountDirectionChanges({0, 1, 1, 0}), 1);
}

TEST(DirectionChangesTest, APlateauOnASlopeIsNoExtremum) {
  EXPECT_EQ(CountDirectionChanges({0, 1, 1, 2, 3}), 0);
}

TEST(DirectionChangesTest, TooShortGraphsHaveNone) {
  EXPECT_EQ(CountDirectionChanges({}), 0);
  EXPECT_EQ(CountDirectionChanges({4.0}), 0);
  EXPECT_EQ(CountDirectionChanges({4.0, -3.0}), 0);
}

TEST(DirectionChangesTest, SmoothSwingOf400FramesWithPeriod40Has19) {
  // 399 samples of a cosine with period 40: interior extrema at t − ½ = 20, 40, … 380.
  EXPECT_EQ(CountDirectionChanges(SmoothSwingGraph(400, 100.0, 40.0)), 19);
}

// [px] What a perfect tracker reads off whole-pixel frames of the benchmark swing (SPEC §3:
// A = 100 px, T = 40 frames, τ = 400 frames). The damping matters: an undamped swing of whole
// periods rounds the same way every period and shows no extra extrema.
std::vector<double> RoundedBenchmarkSwingGraph() {
  return testing::PerfectGraph(testing::PendulumPositions(400, 100.0, 40.0, 400.0));
}

TEST(DirectionChangesTest, WholePixelRoundingInflatesThePlainCount) {
  // SPEC §2.4: ~41 direction changes from rounding alone, where the swing has 19.
  EXPECT_GE(CountDirectionChanges(RoundedBenchmarkSwingGraph()), 35);
}

TEST(DirectionChangesTest, HysteresisBringsTheRoundedSwingBackTo19) {
  EXPECT_EQ(CountDirectionChanges(RoundedBenchmarkSwingGraph(), 1.5), 19);
}

TEST(DirectionChangesTest, HysteresisIgnoresAReversalSmallerThanH) {
  const std::vector<double> graph{0, 3, 2.5, 4, 0};
  EXPECT_EQ(CountDirectionChanges(graph), 3);
  EXPECT_EQ(CountDirectionChanges(graph, 1.0), 1);
}

TEST(DirectionChangesTest, HysteresisCountsAReversalOfExactlyH) {
  EXPECT_EQ(CountDirectionChanges({0, 2, 0.5}, 1.5), 1);
  EXPECT_EQ(CountDirectionChanges({0, 2, 0.6}, 1.5), 0);
}

TEST(DirectionChangesTest, HysteresisMeasuresFromTheRunningExtreme) {
  // The fall from 5 to 3.4 is 1.6 ≥ 1.5 although each step is smaller than h.
  EXPECT_EQ(CountDirectionChanges({0, 5, 4.5, 4.0, 3.4}, 1.5), 1);
}

TEST(DirectionChangesTest, HysteresisWaitsForAFirstMoveOfH) {
  // Nothing counts until the graph has moved h from its start: the early wobble is ignored.
  EXPECT_EQ(CountDirectionChanges({0, 1, 0, 1, 0, 3, 0}, 2.0), 1);
}

TEST(DirectionChangesTest, RefusesANegativeHysteresis) {
  EXPECT_THROW(CountDirectionChanges({0, 1, 0}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
