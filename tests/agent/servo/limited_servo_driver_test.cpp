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
  // A frame period of 1 s: the step bound (120 deg) stays out of the way of the tests of the
  // limits and the rate; LimitedServoDriverStepTest uses a camera's 1/30 s.
  explicit LimitedServoDriverTest(double frame_period_s = 1.0) {
    auto fake = std::make_unique<FakeServoDriver>();
    fake_ = fake.get();
    fake_->SetReadable(false);  // a device that cannot tell where its servos stand
    ServoLimits pan;            // [-45, 45] deg, 120 deg/s, park 0
    ServoLimits tilt;
    tilt.min_deg = -30;
    tilt.max_deg = 10;
    tilt.park_deg = -5;
    driver_ = std::make_unique<LimitedServoDriver>(
        std::move(fake), pan, tilt, [this] { return now_us_; }, frame_period_s);
  }
  // Opens and sends the first command, which puts both axes at park.
  void OpenDriver() {
    std::string error;
    ASSERT_TRUE(driver_->Open(&error)) << error;
    ASSERT_TRUE(driver_->Park(&error)) << error;
  }
  void Advance(double seconds) { now_us_ += static_cast<std::int64_t>(seconds * 1e6); }

  std::int64_t now_us_ = 1'000'000;
  FakeServoDriver* fake_ = nullptr;
  std::unique_ptr<LimitedServoDriver> driver_;
};

// The same at 30 frames/s: one step is at most 120 deg/s · 1/30 s = 4 deg.
class LimitedServoDriverStepTest : public LimitedServoDriverTest {
 protected:
  LimitedServoDriverStepTest() : LimitedServoDriverTest(1.0 / 30) {}
};

TEST_F(LimitedServoDriverTest, OpenMovesNothing) {
  std::string error;
  ASSERT_TRUE(driver_->Open(&error)) << error;
  EXPECT_TRUE(fake_->commands().empty());
  EXPECT_FALSE(driver_->placed());
  EXPECT_FALSE(driver_->AtPark());
}

TEST_F(LimitedServoDriverStepTest, FirstCommandAfterOpenGoesToParkWhateverItAsks) {
  std::string error;
  ASSERT_TRUE(driver_->Open(&error)) << error;
  Advance(1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kTilt, 10, &error)) << error;
  EXPECT_EQ(fake_->angle(ServoAxis::kTilt), -5);
  Advance(1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kTilt, 10, &error)) << error;
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kTilt), -5 + 120.0 / 30);  // one frame's step
}

TEST_F(LimitedServoDriverStepTest, OpenOnADeviceThatTellsItsPositionSlewsFromThere) {
  fake_->SetReadable(true);
  fake_->MoveOnItsOwn(30, 0);
  std::string error;
  ASSERT_TRUE(driver_->Open(&error)) << error;
  EXPECT_TRUE(driver_->placed());
  Advance(1);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, -40, &error)) << error;
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 30 - 120.0 / 30);
}

TEST_F(LimitedServoDriverStepTest, AfterAnyGapOneStepIsAtMostRateTimesFramePeriod) {
  OpenDriver();
  Advance(3600);  // an hour without a command
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 45, nullptr));
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 120.0 / 30);
  EXPECT_DOUBLE_EQ(driver_->max_step_deg(ServoAxis::kPan), 4);
}

TEST_F(LimitedServoDriverStepTest, ReopenSlewsBackFromWhereTheDeviceMovedTheServos) {
  fake_->SetReadable(true);
  OpenDriver();
  for (int i = 0; i < 20; ++i) {
    Advance(0.05);
    ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 40, nullptr));
  }
  ASSERT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 40);
  fake_->Disconnect();
  fake_->MoveOnItsOwn(0, -5);  // a Maestro's serial timeout sent them home
  Advance(10);
  std::string error;
  ASSERT_TRUE(driver_->Reopen(&error)) << error;
  EXPECT_EQ(driver_->angle(ServoAxis::kPan), 0);
  Advance(0.05);
  ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 40, nullptr));
  EXPECT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 4);
}

TEST_F(LimitedServoDriverTest, ReopenMovesNothing) {
  OpenDriver();
  const std::size_t before = fake_->commands().size();
  fake_->Disconnect();
  std::string error;
  ASSERT_TRUE(driver_->Reopen(&error)) << error;
  EXPECT_EQ(fake_->commands().size(), before);
}

TEST_F(LimitedServoDriverStepTest, ParkAndWaitSlewsToParkOneFramePeriodPerStep) {
  OpenDriver();
  for (int i = 0; i < 20; ++i) {
    Advance(0.05);
    ASSERT_TRUE(driver_->SetAngle(ServoAxis::kPan, 40, nullptr));
  }
  ASSERT_DOUBLE_EQ(fake_->angle(ServoAxis::kPan), 40);
  int waits = 0;
  double previous = 40;
  double largest_step = 0;
  std::string error;
  // The clock does not move: the steps are bounded by the frame period, not the time.
  ASSERT_TRUE(driver_->ParkAndWait(
      [&] {
        ++waits;
        largest_step = std::max(largest_step, std::abs(fake_->angle(ServoAxis::kPan) - previous));
        previous = fake_->angle(ServoAxis::kPan);
      },
      &error))
      << error;
  EXPECT_TRUE(driver_->AtPark());
  EXPECT_EQ(fake_->angle(ServoAxis::kPan), 0);
  EXPECT_EQ(waits, 9);  // 40 deg at 4 deg a step: 10 steps, a wait between each
  EXPECT_LE(largest_step, 4 + 1e-9);
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

// Property (issue 10): whatever the sequence of commands, gaps (up to minutes), outages
// (during which the device may move the servos by itself, as a Maestro's serial timeout
// does), reopens and parks, no command moves a servo further than max_rate · frame period
// from where it stood, nor outside the limits.
TEST(LimitedServoDriverPropertyTest, NoSequenceMakesOneStepExceedRateTimesFramePeriod) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    auto owned = std::make_unique<FakeServoDriver>();
    FakeServoDriver* fake = owned.get();
    std::int64_t now_us = 0;
    ServoLimits pan;
    ServoLimits tilt{.min_deg = -30, .max_deg = 10, .max_rate_deg_per_s = 60, .park_deg = -5};
    const double period_s = 1.0 / 60;
    LimitedServoDriver driver(
        std::move(owned), pan, tilt, [&now_us] { return now_us; }, period_s);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> angle(-200, 200);
    std::uniform_int_distribution<int> event(0, 99);
    std::exponential_distribution<double> gap_s(20);  // mostly short, sometimes long
    ASSERT_TRUE(driver.Open(nullptr));
    int violations = 0;
    int steps = 0;
    std::size_t seen = 0;
    for (int i = 0; i < 5000; ++i) {
      const int e = event(rng);
      now_us += static_cast<std::int64_t>((e == 0 ? 300 : gap_s(rng)) * 1e6);
      // Where the servos physically stand before this event's commands.
      double at[2] = {fake->angle(ServoAxis::kPan), fake->angle(ServoAxis::kTilt)};
      if (e < 3) {  // an outage, and the device parks the servos by itself half the time
        fake->Disconnect();
        if (e == 1) fake->MoveOnItsOwn(0, -5);
      } else if (e < 8) {
        driver.Reopen(nullptr);
      } else if (e < 10) {
        driver.ParkAndWait([&now_us] { now_us += 1; }, nullptr);  // even with no time passing
      } else {
        driver.SetAngle(i % 2 ? ServoAxis::kTilt : ServoAxis::kPan, angle(rng), nullptr);
      }
      for (; seen < fake->commands().size(); ++seen) {
        const FakeServoCommand& c = fake->commands()[seen];
        const int a = c.axis == ServoAxis::kPan ? 0 : 1;
        const ServoLimits& l = driver.limits(c.axis);
        if (!(c.deg >= l.min_deg && c.deg <= l.max_deg)) ++violations;
        if (!(std::abs(c.deg - at[a]) <= l.max_rate_deg_per_s * period_s + 1e-9)) ++violations;
        at[a] = c.deg;
        ++steps;
      }
    }
    EXPECT_EQ(violations, 0) << "seed " << seed;
    EXPECT_GT(steps, 1000) << "seed " << seed;
  }
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
