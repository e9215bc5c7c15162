#include "common/control/servo_limits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

namespace kapfix {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(ServoLimitsTest, DefaultsAreValid) {
  std::string error;
  EXPECT_TRUE(ServoLimits{}.IsValid(&error)) << error;
}

TEST(ServoLimitsTest, InvertedRangeIsRejectedWithAReason) {
  ServoLimits limits;
  limits.min_deg = 10;
  limits.max_deg = -10;
  std::string error;
  EXPECT_FALSE(limits.IsValid(&error));
  EXPECT_NE(error.find("min_deg < max_deg"), std::string::npos) << error;
}

TEST(ServoLimitsTest, NonFiniteLimitIsRejected) {
  ServoLimits limits;
  limits.max_deg = kInf;
  EXPECT_FALSE(limits.IsValid(nullptr));
}

TEST(ServoLimitsTest, ZeroRateIsRejected) {
  ServoLimits limits;
  limits.max_rate_deg_per_s = 0;
  EXPECT_FALSE(limits.IsValid(nullptr));
}

TEST(ServoLimitsTest, ParkOutsideTheRangeIsRejected) {
  ServoLimits limits;
  limits.park_deg = 50;
  std::string error;
  EXPECT_FALSE(limits.IsValid(&error));
  EXPECT_NE(error.find("park_deg"), std::string::npos) << error;
}

TEST(ServoLimitsTest, RangeBeyond180DegreesIsRejected) {
  ServoLimits limits;
  limits.min_deg = -200;
  EXPECT_FALSE(limits.IsValid(nullptr));
}

TEST(ServoLimiterTest, InvalidLimitsThrow) {
  ServoLimits limits;
  limits.max_rate_deg_per_s = -1;
  EXPECT_THROW(ServoLimiter{limits}, std::invalid_argument);
}

TEST(ServoLimiterTest, TargetInReachIsReturnedExactly) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(10.0, 0.0, 1.0), 10.0);
}

TEST(ServoLimiterTest, TargetAboveMaxIsClampedToMax) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(90.0, 40.0, 1.0), 45.0);
}

TEST(ServoLimiterTest, NegativeInfinityIsClampedToMin) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(-kInf, -40.0, 1.0), -45.0);
}

TEST(ServoLimiterTest, RateLimitsAStepToRateTimesDt) {
  const ServoLimiter limiter(ServoLimits{});  // 120 deg/s
  EXPECT_DOUBLE_EQ(limiter.Limit(40.0, 0.0, 0.1), 12.0);
  EXPECT_DOUBLE_EQ(limiter.Limit(-40.0, 0.0, 0.1), -12.0);
}

TEST(ServoLimiterTest, NaNTargetKeepsTheCurrentAngle) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(kNaN, 7.5, 1.0), 7.5);
}

TEST(ServoLimiterTest, NonPositiveOrNaNDtAllowsNoMotion) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(30.0, 5.0, 0.0), 5.0);
  EXPECT_EQ(limiter.Limit(30.0, 5.0, -1.0), 5.0);
  EXPECT_EQ(limiter.Limit(30.0, 5.0, kNaN), 5.0);
}

TEST(ServoLimiterTest, InfiniteDtReachesAnyTargetInsideTheLimits) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(-45.0, 45.0, kInf), -45.0);
}

TEST(ServoLimiterTest, CurrentOutsideTheLimitsIsTakenAsTheNearestLimit) {
  const ServoLimiter limiter(ServoLimits{});
  EXPECT_EQ(limiter.Limit(60.0, 80.0, 0.0), 45.0);
}

TEST(ServoLimiterTest, NaNCurrentIsTakenAsPark) {
  ServoLimits limits;
  limits.park_deg = 5;
  const ServoLimiter limiter(limits);
  EXPECT_EQ(limiter.Limit(kNaN, kNaN, 1.0), 5.0);
}

// Property (issue 5, servo safety): whatever is asked — NaN, ±∞, 1e300, ordinary angles — and
// whatever time passes, every commanded angle lies inside [min, max] and no further from the
// previous one than max_rate · dt.
TEST(ServoLimiterTest, RandomCommandsAlwaysEndInsideTheLimitsAndTheRate) {
  ServoLimits limits;
  limits.min_deg = -30;
  limits.max_deg = 50;
  limits.max_rate_deg_per_s = 90;
  limits.park_deg = 10;
  const ServoLimiter limiter(limits);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> angle(-200.0, 200.0);
  std::uniform_real_distribution<double> dt(0.0, 0.2);
  std::uniform_int_distribution<int> kind(0, 9);
  double current = limits.park_deg;
  int outside = 0;
  int too_fast = 0;
  for (int i = 0; i < 10000; ++i) {
    double target = angle(rng);
    switch (kind(rng)) {
      case 0:
        target = kNaN;
        break;
      case 1:
        target = kInf;
        break;
      case 2:
        target = -kInf;
        break;
      case 3:
        target = (i % 2 ? 1 : -1) * 1e300;
        break;
      default:
        break;
    }
    const double step_s = dt(rng);
    const double next = limiter.Limit(target, current, step_s);
    if (!(next >= limits.min_deg && next <= limits.max_deg)) ++outside;
    if (!(std::abs(next - current) <= limits.max_rate_deg_per_s * step_s + 1e-9)) ++too_fast;
    current = next;
  }
  EXPECT_EQ(outside, 0);
  EXPECT_EQ(too_fast, 0);
}

}  // namespace
}  // namespace kapfix
