#include "agent/servo/pca9685_servo_driver.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

// No I2C bus on the machines that run the tests; these check the failure paths and options.

TEST(Pca9685ServoDriverTest, OpenOnAMissingBusNamesItAndTheAddress) {
  Pca9685ServoDriverOptions options;
  options.device = "/dev/i2c-97";
  Pca9685ServoDriver driver(options);
  std::string error;
  EXPECT_FALSE(driver.Open(&error));
  EXPECT_NE(error.find("/dev/i2c-97"), std::string::npos) << error;
  EXPECT_NE(error.find("0x40"), std::string::npos) << error;
}

TEST(Pca9685ServoDriverTest, OpenOnANonI2cDeviceFails) {
  Pca9685ServoDriverOptions options;
  options.device = "/dev/null";
  Pca9685ServoDriver driver(options);
  std::string error;
  EXPECT_FALSE(driver.Open(&error));
  EXPECT_NE(error.find("not an I2C bus"), std::string::npos) << error;
}

TEST(Pca9685ServoDriverTest, SetAngleBeforeOpenFails) {
  Pca9685ServoDriver driver(Pca9685ServoDriverOptions{});
  std::string error;
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, 0, &error));
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
}

TEST(Pca9685ServoDriverTest, AddressOutsideThePca9685RangeIsInvalid) {
  Pca9685ServoDriverOptions options;
  options.address = 0x20;
  EXPECT_FALSE(options.IsValid(nullptr));
}

TEST(Pca9685ServoDriverTest, ChannelBeyond15IsInvalid) {
  Pca9685ServoDriverOptions options;
  options.tilt.channel = 16;
  EXPECT_FALSE(options.IsValid(nullptr));
}

TEST(Pca9685ServoDriverTest, PulseLongerThanThePeriodIsInvalid) {
  Pca9685ServoDriverOptions options;
  options.pwm_hz = 500;  // 2 ms period: a 2000 µs pulse never ends
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("period"), std::string::npos) << error;
}

TEST(Pca9685ServoDriverTest, DescribeNamesBusAddressAndChannels) {
  EXPECT_EQ(Pca9685ServoDriver(Pca9685ServoDriverOptions{}).Describe(),
            "pca9685 /dev/i2c-1 @0x40 (pan ch 0, tilt ch 1)");
}

}  // namespace
}  // namespace kapfix::agent
