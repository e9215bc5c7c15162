// The dead band and rate limit every controller kind applies through its gains.
#include "common/control/controller.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

TEST(ControllerGainsTest, ADisplacementInsideTheDeadBandIsNotCorrected) {
  ControllerGains gains;
  gains.dead_band_px = 2;
  EXPECT_DOUBLE_EQ(gains.Correctable(1.9), 0);
  EXPECT_DOUBLE_EQ(gains.Correctable(-1.9), 0);
  EXPECT_DOUBLE_EQ(gains.Correctable(2), 2);  // the band's edge is corrected
  EXPECT_DOUBLE_EQ(gains.Correctable(-3.5), -3.5);
}

TEST(ControllerGainsTest, BeyondDeadBandIsTheExcessOverIt) {
  ControllerGains gains;
  gains.dead_band_px = 2;
  EXPECT_DOUBLE_EQ(gains.BeyondDeadBand(1), 0);
  EXPECT_DOUBLE_EQ(gains.BeyondDeadBand(-5), 3);
}

TEST(ControllerGainsTest, WithoutRateLimitKeepsEveryOtherGain) {
  ControllerGains gains;
  gains.p = 0.7;
  gains.dead_band_px = 2;
  gains.rate_limit_deg_per_s = 10;
  const ControllerGains unlimited = gains.WithoutRateLimit();
  EXPECT_DOUBLE_EQ(unlimited.p, 0.7);
  EXPECT_DOUBLE_EQ(unlimited.dead_band_px, 2);
  EXPECT_DOUBLE_EQ(unlimited.LimitRate({5, -5}, {0, 0}, 0.1).pan_deg, 5);
  EXPECT_DOUBLE_EQ(gains.LimitRate({5, -5}, {0, 0}, 0.1).pan_deg, 1);
}

}  // namespace
}  // namespace kapfix
