#include "common/sim/simulated_servo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace kapfix {
namespace {

// A servo with one effect at a time switched on by the test.
SimulatedServoOptions Ideal() {
  SimulatedServoOptions o;
  o.rate_limit_deg_per_frame = 1000;
  o.dead_band_deg = 0;
  o.backlash_deg = 0;
  o.latency_frames = 0;
  return o;
}

TEST(SimulatedServoTest, LatencyDelaysACommandByExactlyThatManySteps) {
  SimulatedServoOptions o = Ideal();
  o.latency_frames = 3;
  SimulatedServo servo(o);
  servo.Command(10);
  EXPECT_EQ(servo.commanded(), 10);
  EXPECT_EQ(servo.Step(), 0);
  EXPECT_EQ(servo.Step(), 0);
  EXPECT_EQ(servo.Step(), 0);
  EXPECT_EQ(servo.Step(), 10);
}

TEST(SimulatedServoTest, ZeroLatencyActsOnTheNextStep) {
  SimulatedServo servo(Ideal());
  servo.Command(-7);
  EXPECT_EQ(servo.Step(), -7);
  EXPECT_EQ(servo.angle(), -7);
}

TEST(SimulatedServoTest, LaterCommandsTakeOverAfterTheirOwnDelay) {
  SimulatedServoOptions o = Ideal();
  o.latency_frames = 2;
  SimulatedServo servo(o);
  servo.Command(10);
  EXPECT_EQ(servo.Step(), 0);
  servo.Command(-10);
  EXPECT_EQ(servo.Step(), 0);
  EXPECT_EQ(servo.Step(), 10);   // the first command, two Steps after it was sent
  EXPECT_EQ(servo.Step(), -10);  // the second, two Steps after it was sent
}

TEST(SimulatedServoTest, RateLimitBoundsTheMovePerStep) {
  SimulatedServoOptions o = Ideal();
  o.rate_limit_deg_per_frame = 3;
  SimulatedServo servo(o);
  servo.Command(10);
  EXPECT_DOUBLE_EQ(servo.Step(), 3);
  EXPECT_DOUBLE_EQ(servo.Step(), 6);
  EXPECT_DOUBLE_EQ(servo.Step(), 9);
  EXPECT_DOUBLE_EQ(servo.Step(), 10);
  servo.Command(4);
  EXPECT_DOUBLE_EQ(servo.Step(), 7);
}

TEST(SimulatedServoTest, DeadBandIgnoresSmallerMoves) {
  SimulatedServoOptions o = Ideal();
  o.dead_band_deg = 0.5;
  SimulatedServo servo(o);
  servo.Command(0.3);
  EXPECT_EQ(servo.Step(), 0);
  EXPECT_EQ(servo.Step(), 0);
  servo.Command(0.6);
  EXPECT_DOUBLE_EQ(servo.Step(), 0.6);
  servo.Command(0.2);  // 0.4 away: inside the dead band again
  EXPECT_DOUBLE_EQ(servo.Step(), 0.6);
}

TEST(SimulatedServoTest, BacklashHoldsTheOutputUntilTheGapIsTakenUp) {
  SimulatedServoOptions o = Ideal();
  o.backlash_deg = 1.0;
  SimulatedServo servo(o);
  servo.Command(10);
  EXPECT_DOUBLE_EQ(servo.Step(), 9.5);  // dragged: trails the shaft by half the gap
  EXPECT_DOUBLE_EQ(servo.shaft(), 10);
  // Reversal: the shaft crosses the whole gap (1°) before the output moves.
  for (double shaft : {9.8, 9.5, 9.2, 9.0}) {
    servo.Command(shaft);
    EXPECT_DOUBLE_EQ(servo.Step(), 9.5) << "shaft " << shaft;
  }
  servo.Command(8.0);
  EXPECT_DOUBLE_EQ(servo.Step(), 8.5);
  // Forward again: the same hysteresis the other way.
  servo.Command(9.0);
  EXPECT_DOUBLE_EQ(servo.Step(), 8.5);
  servo.Command(9.5);
  EXPECT_DOUBLE_EQ(servo.Step(), 9.0);
}

TEST(SimulatedServoTest, AbsurdCommandsAreClampedToTheLimits) {
  SimulatedServoOptions o;  // defaults: ±45°, 3°/frame, backlash, latency 1
  SimulatedServo servo(o);
  servo.Command(1e9);
  EXPECT_EQ(servo.commanded(), 45);
  for (int i = 0; i < 40; ++i) {
    const double a = servo.Step();
    ASSERT_LE(a, 45.0);
    ASSERT_GE(a, -45.0);
  }
  EXPECT_NEAR(servo.angle(), 45, 0.1);
  servo.Command(-std::numeric_limits<double>::infinity());
  EXPECT_EQ(servo.commanded(), -45);
  for (int i = 0; i < 40; ++i) {
    const double a = servo.Step();
    ASSERT_LE(a, 45.0);
    ASSERT_GE(a, -45.0);
  }
  EXPECT_NEAR(servo.angle(), -45, 0.1);
}

TEST(SimulatedServoTest, NanCommandIsIgnoredAndTheServoStaysPut) {
  SimulatedServo servo(Ideal());
  servo.Command(12);
  servo.Step();
  servo.Command(std::nan(""));
  EXPECT_EQ(servo.commanded(), 12);
  EXPECT_EQ(servo.Step(), 12);
  EXPECT_EQ(servo.Step(), 12);
}

TEST(SimulatedServoTest, StartsAtTheInitialAngle) {
  SimulatedServoOptions o = Ideal();
  o.initial_deg = 20;
  SimulatedServo servo(o);
  EXPECT_EQ(servo.angle(), 20);
  EXPECT_EQ(servo.commanded(), 20);
  EXPECT_EQ(servo.Step(), 20);
}

TEST(SimulatedServoTest, InvalidOptionsAreRejectedWithAReason) {
  SimulatedServoOptions o;
  o.min_deg = 10;
  o.max_deg = -10;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("limits"), std::string::npos) << error;
  EXPECT_THROW(SimulatedServo{o}, std::invalid_argument);
  o = SimulatedServoOptions{};
  o.initial_deg = 50;
  EXPECT_FALSE(o.IsValid(nullptr));
  o = SimulatedServoOptions{};
  o.rate_limit_deg_per_frame = 0;
  EXPECT_FALSE(o.IsValid(nullptr));
  o = SimulatedServoOptions{};
  o.latency_frames = -1;
  EXPECT_FALSE(o.IsValid(nullptr));
}

TEST(SimulatedServoTest, LatencyJitterDelaysEachCommandByOneToNFrames) {
  SimulatedServoOptions o;
  o.latency_frames = 1;
  o.latency_max_frames = 4;
  o.dead_band_deg = 0;
  o.backlash_deg = 0;
  o.rate_limit_deg_per_frame = 100;
  std::set<int> delays;
  for (int trial = 0; trial < 40; ++trial) {
    o.seed = static_cast<std::uint32_t>(trial + 1);
    SimulatedServo servo(o);
    servo.Command(10.0);
    int steps = 0;
    while (servo.angle() != 10.0 && steps < 10) {
      servo.Step();
      ++steps;
    }
    delays.insert(steps - 1);  // Steps without motion before the one that moved
  }
  EXPECT_EQ(delays, (std::set<int>{1, 2, 3, 4}));
}

TEST(SimulatedServoTest, AnOvertakenCommandIsNeverFollowed) {
  SimulatedServoOptions o;
  o.latency_frames = 1;
  o.latency_max_frames = 6;
  o.dead_band_deg = 0;
  o.backlash_deg = 0;
  o.rate_limit_deg_per_frame = 100;
  for (std::uint32_t seed = 1; seed <= 30; ++seed) {
    o.seed = seed;
    SimulatedServo servo(o);
    // Targets grow with each command: once the servo has followed one, an older (smaller)
    // one arriving late must not pull it back.
    double highest = 0;
    for (int k = 1; k <= 20; ++k) {
      servo.Command(k);
      servo.Step();
      EXPECT_GE(servo.angle(), highest) << "seed " << seed << " step " << k;
      highest = std::max(highest, servo.angle());
    }
  }
}

TEST(SimulatedServoTest, LatencyJitterBelowTheLatencyIsRejected) {
  SimulatedServoOptions o;
  o.latency_frames = 3;
  o.latency_max_frames = 2;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("jitter"), std::string::npos);
}

}  // namespace
}  // namespace kapfix
