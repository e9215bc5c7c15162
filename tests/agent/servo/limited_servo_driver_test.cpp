#include "agent/servo/limited_servo_driver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "agent/servo/fake_servo_driver.hpp"

namespace kapfix::agent {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A LimitedServoDriver over a FakeServoDriver with a clock the test moves by hand.
class LimitedServoDriverTest : public ::testing::Test {
 protected:
  LimitedServoDriverTest() {
    auto fake = std::make_unique<FakeServoDriver>();
    fake_ = fake.get();
    ServoLimits pan;  // [-45, 45] deg, 120 deg/s, park 0
    ServoLimits tilt;
    tilt.min_deg = -30;
    tilt.max_deg = 10;
    tilt.park_deg = -5;
    driver_ = std::make_unique<LimitedServoDriver>(std::move(fake), pan, tilt,
                                                   [this] { return now_us_; });
  }
  void OpenDriver() {
    std::string error;
    ASSERT_TRUE(driver_->Open(&error)) << error;
  }
  void Advance(double seconds) { now_us_ += static_cast<std::int64_t>(seconds * 1e6); }

  std::int64_t now_us_ = 1'000'000;
  FakeServoDriver* fake_ = nullptr;
  std::unique_ptr<LimitedServoDriver> driver_;
};

TEST_F(LimitedServoDriverTest, OpenSendsEachAxisToItsPark) {
  OpenDriver();
  EXPECT_EQ(fake_->angle(ServoAxis::kPan), 0);
  EXPECT_EQ(fake_->angle(ServoAxis::kTilt), -5);
}

TEST_F(LimitedServoDriverTest, CommandsBeforeOpenFail) {
  std::string error;
  EXPECT_FALSE(driver_->SetAngle(ServoAxis::kPan, 1, &error));
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
}

TEST_F(LimitedServoDriverTest, BackendOpenFailureIsPassedOn) {
  fake_->FailOpen(true);
  std::string error;
  EXPECT_FALSE(driver_->Open(&error));
  EXPECT_NE(error.find("fake servos"), std::string::npos) << error;
}

TEST_F(LimitedServoDriverTest, CommandInsideLimitsAndRateReachesTheBackendUnchanged) {
  OpenDriver();
  Advance(0.1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 10, nullptr));
  EXPECT_EQ(fake_->angle(ServoAxis::kPan), 10);
  EXPECT_EQ(driver_->limited_count(), 0u);
}

TEST_F(LimitedServoDriverTest, CommandBeyondMaxIsClamped) {
  OpenDriver();
  Advance(10);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kTilt, 40, nullptr));
  EXPECT_EQ(fake_->angle(ServoAxis::kTilt), 10);
  EXPECT_EQ(driver_->limited_count(), 1u);
}

TEST_F(LimitedServoDriverTest, RateIsLimitedByTheTimeSinceTheLastCommand) {
  OpenDriver();
  Advance(0.05);  // 120 deg/s · 0.05 s = 6 deg
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 30, nullptr));
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 6);
}

TEST_F(LimitedServoDriverTest, AxesKeepTheirOwnClocks) {
  OpenDriver();
  Advance(0.05);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 30, nullptr));
  Advance(0.05);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kTilt, -30, nullptr));  // 0.1 s since Open: 12 deg
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kTilt), -17);
}

TEST_F(LimitedServoDriverTest, NaNIsRefusedWithAnErrorAndNoMotion) {
  OpenDriver();
  const std::size_t before = fake_->commands().size();
  Advance(1);
  std::string error;
  EXPECT_FALSE(driver_->SetAngle(ServoAxis::kPan, kNaN, &error));
  EXPECT_NE(error.find("non-finite"), std::string::npos) << error;
  EXPECT_EQ(fake_->commands().size(), before);
  EXPECT_EQ(driver_->refused_count(), 1u);
}

TEST_F(LimitedServoDriverTest, InfinityIsRefusedWithNoMotion) {
  OpenDriver();
  const std::size_t before = fake_->commands().size();
  Advance(1);
  EXPECT_FALSE(driver_->SetAngle(ServoAxis::kTilt, -kInf, nullptr));
  EXPECT_EQ(fake_->commands().size(), before);
}

TEST_F(LimitedServoDriverTest, FailedBackendCommandKeepsTheLastAngle) {
  OpenDriver();
  Advance(1);
  fake_->FailNextCommands(1);
  std::string error;
  EXPECT_FALSE(driver_->SetAngle(ServoAxis::kPan, 20, &error));
  EXPECT_EQ(driver_->angle(ServoAxis::kPan), 0);
}

TEST_F(LimitedServoDriverTest, ParkMovesTowardsParkAtTheRate) {
  OpenDriver();
  Advance(1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 40, nullptr));
  Advance(0.1);  // 12 deg
  ASSERT_TRUE(driver_->Park(nullptr));
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 28);
  EXPECT_FALSE(driver_->AtPark());
}

TEST_F(LimitedServoDriverTest, ParkAfterALongStallReachesParkInOneCall) {
  OpenDriver();
  Advance(1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 40, nullptr));
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kTilt, 10, nullptr));
  Advance(0.5);
  ASSERT_TRUE(driver_->Park(nullptr));
  EXPECT_TRUE(driver_->AtPark());
  EXPECT_EQ(fake_->angle(ServoAxis::kTilt), -5);
}

TEST_F(LimitedServoDriverTest, ParkTriesTheSecondAxisWhenTheFirstFails) {
  OpenDriver();
  Advance(1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kTilt, 10, nullptr));
  Advance(1);
  fake_->FailNextCommands(1);  // the pan command
  std::string error;
  EXPECT_FALSE(driver_->Park(&error));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(fake_->angle(ServoAxis::kTilt), -5);
}

TEST_F(LimitedServoDriverTest, DescribeShowsTheBackendAndTheLimits) {
  EXPECT_EQ(driver_->Describe(),
            "fake servos, limits pan [-45, 45] deg ≤ 120 deg/s, tilt [-30, 10] deg ≤ 120 deg/s");
}

// Property (issue 5): random commands, including NaN, ±∞ and absurd values, at random
// intervals, never reach the backend outside the limits or faster than the rate.
TEST_F(LimitedServoDriverTest, RandomCommandsNeverReachTheBackendOutsideLimitsOrRate) {
  OpenDriver();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-500, 500);
  std::uniform_int_distribution<int> kind(0, 7);
  std::uniform_int_distribution<std::int64_t> step_us(0, 50'000);
  double last[2] = {0, -5};
  std::int64_t last_us[2] = {now_us_, now_us_};
  int violations = 0;
  for (int i = 0; i < 10000; ++i) {
    const ServoAxis axis = i % 2 ? ServoAxis::kTilt : ServoAxis::kPan;
    const int a = i % 2;
    double target = angle(rng);
    const int k = kind(rng);
    if (k == 0) target = kNaN;
    if (k == 1) target = kInf;
    if (k == 2) target = -kInf;
    if (k == 3) target = 1e300;
    now_us_ += step_us(rng);
    const std::size_t before = fake_->commands().size();
    driver_->SetAngle(axis, target, nullptr);
    if (fake_->commands().size() == before) continue;  // refused: nothing reached the backend
    const double sent = fake_->commands().back().deg;
    const ServoLimits& l = driver_->limits(axis);
    const double dt = static_cast<double>(now_us_ - last_us[a]) * 1e-6;
    if (!(sent >= l.min_deg && sent <= l.max_deg)) ++violations;
    if (!(std::abs(sent - last[a]) <= l.max_rate_deg_per_s * dt + 1e-9)) ++violations;
    last[a] = sent;
    last_us[a] = now_us_;
  }
  EXPECT_EQ(violations, 0);
}

TEST(LimitedServoDriverConstructionTest, InvalidLimitsThrow) {
  ServoLimits bad;
  bad.park_deg = 90;
  EXPECT_THROW(LimitedServoDriver(std::make_unique<FakeServoDriver>(), bad, ServoLimits{}),
               std::invalid_argument);
}

TEST(LimitedServoDriverConstructionTest, NullBackendThrows) {
  EXPECT_THROW(LimitedServoDriver(nullptr, ServoLimits{}, ServoLimits{}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix::agent
