#include "agent/servo/fake_servo_driver.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

TEST(FakeServoDriverTest, RecordsSuccessfulCommands) {
  FakeServoDriver driver;
  ASSERT_TRUE(driver.Open(nullptr));
  ASSERT_TRUE(driver.SetAngle(ServoAxis::kTilt, 12.5, nullptr));
  ASSERT_EQ(driver.commands().size(), 1u);
  EXPECT_EQ(driver.commands()[0].axis, ServoAxis::kTilt);
  EXPECT_EQ(driver.commands()[0].deg, 12.5);
  EXPECT_EQ(driver.angle(ServoAxis::kTilt), 12.5);
}

TEST(FakeServoDriverTest, CommandsBeforeOpenFail) {
  FakeServoDriver driver;
  std::string error;
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, 1, &error));
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
}

TEST(FakeServoDriverTest, FailsTheRequestedNumberOfCommandsWithoutMoving) {
  FakeServoDriver driver;
  ASSERT_TRUE(driver.Open(nullptr));
  driver.FailNextCommands(1);
  std::string error;
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, 5, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(driver.angle(ServoAxis::kPan), 0);
  EXPECT_TRUE(driver.SetAngle(ServoAxis::kPan, 5, nullptr));
  EXPECT_EQ(driver.commands().size(), 1u);
}

TEST(FakeServoDriverTest, ParkIsRecordedAndCentresBothAxes) {
  FakeServoDriver driver;
  ASSERT_TRUE(driver.Open(nullptr));
  ASSERT_TRUE(driver.SetAngle(ServoAxis::kPan, 5, nullptr));
  ASSERT_TRUE(driver.Park(nullptr));
  EXPECT_EQ(driver.commands().back().kind, FakeServoCommand::Kind::kPark);
  EXPECT_EQ(driver.angle(ServoAxis::kPan), 0);
}

TEST(FakeServoDriverTest, FailOpenSimulatesAMissingController) {
  FakeServoDriver driver;
  driver.FailOpen(true);
  EXPECT_FALSE(driver.Open(nullptr));
  EXPECT_EQ(driver.open_count(), 0);
}

}  // namespace
}  // namespace kapfix::agent
