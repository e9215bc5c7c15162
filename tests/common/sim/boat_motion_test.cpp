#include "common/sim/boat_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace kapfix {
namespace {

double Roll(double t) { return 60 * std::sin(2 * std::numbers::pi * t / 120); }

TEST(BoatMotionTest, RollIsMostlyAlongY) {
  const BoatMotion boat(BoatMotionOptions{});
  double sx = 0, sy = 0;
  for (int t = 0; t < 1200; ++t) {
    const cv::Point2d p = boat.LineOfSight(t);
    sx += p.x * p.x;
    sy += p.y * p.y;
  }
  EXPECT_GT(std::sqrt(sy / sx), 20.0);
}

TEST(BoatMotionTest, WithoutWavesYIsThePureRoll) {
  BoatMotionOptions o;
  o.waves = 0;
  const BoatMotion boat(o);
  EXPECT_TRUE(boat.waves().empty());
  for (int t = 0; t < 240; ++t) ASSERT_DOUBLE_EQ(boat.LineOfSight(t).y, Roll(t)) << t;
  EXPECT_DOUBLE_EQ(boat.LineOfSight(30).y, 60.0);
}

TEST(BoatMotionTest, WavesAreDrawnWithinTheirBounds) {
  BoatMotionOptions o;
  o.waves = 40;
  const BoatMotion boat(o);
  ASSERT_EQ(boat.waves().size(), 40u);
  double longest = 0, shortest = 1e9;
  for (const BoatWave& w : boat.waves()) {
    EXPECT_GE(w.amplitude_px, 0.0);
    EXPECT_LE(w.amplitude_px, 8.0);
    EXPECT_GE(w.period_frames, 7.0);
    EXPECT_LE(w.period_frames, 30.0);
    EXPECT_GE(w.phase_rad, 0.0);
    EXPECT_LT(w.phase_rad, 2 * std::numbers::pi);
    longest = std::max(longest, w.period_frames);
    shortest = std::min(shortest, w.period_frames);
  }
  EXPECT_GT(longest - shortest, 15.0) << "periods should spread over 7…30 frames";
}

TEST(BoatMotionTest, YIsTheRollPlusTheListedWaves) {
  const BoatMotion boat(BoatMotionOptions{});
  ASSERT_EQ(boat.waves().size(), 3u);
  for (int t = 0; t < 240; ++t) {
    double y = Roll(t);
    for (const BoatWave& w : boat.waves()) {
      y += w.amplitude_px * std::sin(2 * std::numbers::pi * t / w.period_frames + w.phase_rad);
    }
    ASSERT_NEAR(boat.LineOfSight(t).y, y, 1e-9) << t;
    ASSERT_LE(std::abs(boat.LineOfSight(t).y - Roll(t)), 3 * 8.0) << t;
  }
}

TEST(BoatMotionTest, SameSeedGivesIdenticalPositions) {
  const BoatMotion a(BoatMotionOptions{}), b(BoatMotionOptions{});
  for (int t = 300; t >= 0; --t) ASSERT_EQ(a.LineOfSight(t), b.LineOfSight(t)) << t;
}

TEST(BoatMotionTest, DifferentSeedGivesDifferentWavesAndJitter) {
  BoatMotionOptions o;
  const BoatMotion a(o);
  o.seed = 9;
  const BoatMotion b(o);
  EXPECT_NE(a.waves()[0].period_frames, b.waves()[0].period_frames);
  EXPECT_NE(a.LineOfSight(17).x, b.LineOfSight(17).x);
  EXPECT_NE(a.LineOfSight(17).y, b.LineOfSight(17).y);
}

TEST(BoatMotionTest, InvalidOptionsAreRejectedWithAReason) {
  BoatMotionOptions o;
  o.waves = -1;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("waves"), std::string::npos) << error;
  EXPECT_THROW(BoatMotion{o}, std::invalid_argument);
  o = BoatMotionOptions{};
  o.roll_period_frames = -3;
  EXPECT_FALSE(o.IsValid(nullptr));
}

}  // namespace
}  // namespace kapfix
