#include "agent/servo/servo_channel_mapping.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace kapfix::agent {
namespace {

TEST(ServoChannelMappingTest, ZeroDegreesIsTheCentrePulse) {
  EXPECT_EQ(ServoChannelMapping{}.PulseUs(0), 1500);
}

TEST(ServoChannelMappingTest, PulseIsLinearInTheAngle) {
  ServoChannelMapping m;
  m.us_per_deg = 11;
  EXPECT_DOUBLE_EQ(m.PulseUs(20), 1720);
}

TEST(ServoChannelMappingTest, NegativeSlopeReversesTheDirection) {
  ServoChannelMapping m;
  m.us_per_deg = -10;
  EXPECT_DOUBLE_EQ(m.PulseUs(20), 1300);
}

TEST(ServoChannelMappingTest, PulseIsClampedToTheMappingRange) {
  ServoChannelMapping m;
  EXPECT_EQ(m.PulseUs(1000), 2000);
  EXPECT_EQ(m.PulseUs(-std::numeric_limits<double>::infinity()), 1000);
}

TEST(ServoChannelMappingTest, NaNGivesTheCentrePulse) {
  EXPECT_EQ(ServoChannelMapping{}.PulseUs(std::numeric_limits<double>::quiet_NaN()), 1500);
}

TEST(ServoChannelMappingTest, ChannelBeyondTheControllerIsInvalid) {
  ServoChannelMapping m;
  m.channel = 16;
  std::string error;
  EXPECT_FALSE(m.IsValid(16, &error));
  EXPECT_NE(error.find("channel"), std::string::npos) << error;
}

TEST(ServoChannelMappingTest, ZeroSlopeIsInvalid) {
  ServoChannelMapping m;
  m.us_per_deg = 0;
  EXPECT_FALSE(m.IsValid(24, nullptr));
}

TEST(ServoChannelMappingTest, PulseRangeBeyond2600UsIsInvalid) {
  ServoChannelMapping m;
  m.max_us = 3000;
  EXPECT_FALSE(m.IsValid(24, nullptr));
}

}  // namespace
}  // namespace kapfix::agent
