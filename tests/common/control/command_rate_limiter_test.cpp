#include "common/control/command_rate_limiter.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

ControllerGains Rate(double deg_per_s) {
  ControllerGains gains;
  gains.rate_limit_deg_per_s = deg_per_s;
  return gains;
}

TEST(CommandRateLimiterTest, TheFirstTargetMovesAtMostTheRateTimesTheIntervalFromCurrent) {
  CommandRateLimiter limiter;
  const ServoTargets limited = limiter.Limit(Rate(10), {5, -5}, {0, 0}, 0.1);
  EXPECT_DOUBLE_EQ(limited.pan_deg, 1);
  EXPECT_DOUBLE_EQ(limited.tilt_deg, -1);
}

TEST(CommandRateLimiterTest, WithoutARateTheTargetPasses) {
  CommandRateLimiter limiter;
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(0), {5, -5}, {0, 0}, 0.1).pan_deg, 5);
}

// With an actuation delay the angles a frame was seen through lag the commands: the limit
// counts from the previous command, so the commands advance every frame, not every n.
TEST(CommandRateLimiterTest, TargetsAdvanceFromThePreviousOneNotFromALaggingCurrent) {
  CommandRateLimiter limiter;
  const ServoTargets seen{0, 0};  // still the angles of three commands ago
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {10, 0}, seen, 0.1).pan_deg, 2);
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {10, 0}, seen, 0.1).pan_deg, 4);
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {10, 0}, seen, 0.1).pan_deg, 6);
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {5, 0}, seen, 0.1).pan_deg, 5);
}

TEST(CommandRateLimiterTest, WithoutElapsedTimeThePreviousTargetStands) {
  CommandRateLimiter limiter;
  limiter.Limit(Rate(20), {1, 1}, {0, 0}, 0.1);
  const ServoTargets held = limiter.Limit(Rate(20), {9, 9}, {0, 0}, 0.0);
  EXPECT_DOUBLE_EQ(held.pan_deg, 1);
  EXPECT_DOUBLE_EQ(held.tilt_deg, 1);
}

TEST(CommandRateLimiterTest, UnmeasuredHoldsAtCurrentAndTheNextLimitStartsThere) {
  CommandRateLimiter limiter;
  limiter.Limit(Rate(20), {10, 0}, {0, 0}, 0.1);
  ControlInput input;
  input.dt_s = 0.1;
  EXPECT_DOUBLE_EQ(limiter.Unmeasured(Rate(20), input, {7, 0}).pan_deg, 7);
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {10, 0}, {0, 0}, 0.1).pan_deg, 9);
}

TEST(CommandRateLimiterTest, UnmeasuredWithAReturnHeadsThereFromThePreviousTarget) {
  CommandRateLimiter limiter;
  limiter.Limit(Rate(20), {10, 0}, {0, 0}, 0.1);  // 2
  ControlInput input;
  input.dt_s = 0.1;
  input.return_to = ServoTargets{-5, 1};
  const ServoTargets first = limiter.Unmeasured(Rate(20), input, {7, 0});
  EXPECT_DOUBLE_EQ(first.pan_deg, 0);
  EXPECT_DOUBLE_EQ(first.tilt_deg, 1);
}

TEST(CommandRateLimiterTest, AfterResetItCountsFromCurrentAgain) {
  CommandRateLimiter limiter;
  limiter.Limit(Rate(20), {10, 0}, {0, 0}, 0.1);
  limiter.Reset();
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {10, 0}, {7, 0}, 0.1).pan_deg, 9);
}

TEST(CommandRateLimiterTest, AHoldIssuedUnlimitedIsWhereTheNextLimitStarts) {
  CommandRateLimiter limiter;
  limiter.Limit(Rate(20), {10, 0}, {0, 0}, 0.1);
  limiter.Issued({-3, 0});
  EXPECT_DOUBLE_EQ(limiter.Limit(Rate(20), {10, 0}, {0, 0}, 0.1).pan_deg, -1);
}

}  // namespace
}  // namespace kapfix
