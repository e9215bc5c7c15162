#include "agent/pipeline/servo_commander.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <memory>
#include <thread>

#include "agent/servo/fake_servo_driver.hpp"

namespace kapfix::agent {
namespace {

// Fake servos behind the real limits, on a clock the test moves.
struct Rig {
  std::int64_t now_us = 0;
  FakeServoDriver* fake = nullptr;
  std::unique_ptr<LimitedServoDriver> servos;
  std::mutex mutex;
  std::unique_ptr<ServoCommander> commander;

  Rig() {
    auto backend = std::make_unique<FakeServoDriver>();
    fake = backend.get();
    // A frame period of 1 s: the step bound (120 deg) never holds a command back here, so what
    // the tests see is the commander's doing.
    servos = std::make_unique<LimitedServoDriver>(
        std::move(backend), ServoLimits{}, ServoLimits{}, [this] { return now_us; }, 1.0);
    std::string error;
    EXPECT_TRUE(servos->Open(&error)) << error;
    ServoCommanderOptions options;
    options.retry_initial_ms = 100;
    options.retry_max_ms = 400;
    options.reopen_in_background = false;
    commander = std::make_unique<ServoCommander>(*servos, mutex, std::move(options),
                                                 [this] { return now_us; });
  }
  void AdvanceMs(int ms) { now_us += std::int64_t{ms} * 1000; }
};

TEST(ServoCommanderTest, CommandsReachTheServos) {
  Rig rig;
  rig.AdvanceMs(1000);
  const ServoTargets angles = rig.commander->Command({2.0, -1.0});
  EXPECT_DOUBLE_EQ(angles.pan_deg, 2.0);
  EXPECT_DOUBLE_EQ(rig.fake->angle(ServoAxis::kTilt), -1.0);
  EXPECT_FALSE(rig.commander->out());
}

TEST(ServoCommanderTest, AFailingDriverHoldsTheServosWhereTheyWere) {
  Rig rig;
  rig.AdvanceMs(1000);
  rig.commander->Command({2.0, 1.0});
  rig.fake->Disconnect();
  rig.AdvanceMs(10);
  const ServoTargets held = rig.commander->Command({3.0, 1.5});
  EXPECT_TRUE(rig.commander->out());
  EXPECT_DOUBLE_EQ(held.pan_deg, 2.0);
  const std::size_t sent = rig.fake->commands().size();
  rig.AdvanceMs(10);
  rig.commander->Command({4.0, 2.0});  // before the first retry: nothing is sent
  EXPECT_EQ(rig.fake->commands().size(), sent);
  EXPECT_EQ(rig.commander->counters().outages, 1U);
}

TEST(ServoCommanderTest, TheDriverIsReopenedWithDoublingBackOff) {
  Rig rig;
  rig.fake->Disconnect();
  rig.fake->FailOpen(true);
  rig.commander->Command({1.0, 0.0});  // t = 0: fails; retries due at 100, 300, 700, 1100 ms
  const int opened = rig.fake->open_count();
  for (int ms = 0; ms < 1200; ms += 10) {
    rig.AdvanceMs(10);
    rig.commander->Command({1.0, 0.0});
  }
  EXPECT_TRUE(rig.commander->out());
  EXPECT_EQ(rig.fake->open_count(), opened) << "no Open succeeded";
  rig.fake->FailOpen(false);
  // The next retry is due 400 ms (the cap) after the one at 1100 ms.
  rig.AdvanceMs(290);
  rig.commander->Command({1.0, 0.0});
  EXPECT_TRUE(rig.commander->out()) << "retried before the back-off allowed";
  rig.AdvanceMs(20);
  rig.commander->Command({1.0, 0.0});
  EXPECT_FALSE(rig.commander->out());
  EXPECT_EQ(rig.fake->open_count(), opened + 1);
}

TEST(ServoCommanderTest, FixationResumesFromTheLastAnglesOnceTheDriverIsBack) {
  Rig rig;
  rig.AdvanceMs(1000);
  rig.commander->Command({5.0, -2.0});
  rig.fake->Disconnect();
  rig.AdvanceMs(10);
  rig.commander->Command({6.0, -2.0});
  rig.AdvanceMs(100);
  const std::size_t before = rig.fake->commands().size();
  const ServoTargets reopened = rig.commander->Command({6.0, -2.0});
  EXPECT_FALSE(rig.commander->out());
  EXPECT_EQ(rig.commander->counters().recoveries, 1U);
  // Reopened where the device says the servos stand, (5, −2), and nothing sent on reopen:
  // the first command after it does not move them (no time since the reopen).
  ASSERT_GT(rig.fake->commands().size(), before);
  EXPECT_DOUBLE_EQ(rig.fake->commands()[before].deg, 5.0);
  EXPECT_DOUBLE_EQ(reopened.pan_deg, 5.0);
  // And the next frame's target is reached as the rate limit allows.
  rig.AdvanceMs(100);
  EXPECT_DOUBLE_EQ(rig.commander->Command({6.0, -2.0}).pan_deg, 6.0);
}

// A servo driver whose Open waits until the test lets it finish (a Maestro taking its answer
// timeout, a slow USB setup).
class SlowOpenServoDriver : public FakeServoDriver {
 public:
  bool Open(std::string* error) override {
    if (hold_) {
      std::unique_lock lock(mutex_);
      entered_ = true;
      changed_.notify_all();
      changed_.wait(lock, [this] { return released_; });
    }
    return FakeServoDriver::Open(error);
  }
  void Hold() { hold_ = true; }
  void WaitUntilOpening() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return entered_; });
  }
  void Release() {
    std::lock_guard lock(mutex_);
    released_ = true;
    changed_.notify_all();
  }

 private:
  std::atomic<bool> hold_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  bool entered_ = false;
  bool released_ = false;
};

TEST(ServoCommanderTest, ASlowReopenRunsBesideTheControlLoopWithoutHoldingItUp) {
  std::int64_t now_us = 0;
  auto backend = std::make_unique<SlowOpenServoDriver>();
  SlowOpenServoDriver* fake = backend.get();
  LimitedServoDriver servos(std::move(backend), ServoLimits{}, ServoLimits{},
                            [&now_us] { return now_us; });
  ASSERT_TRUE(servos.Open(nullptr));
  std::mutex mutex;
  ServoCommanderOptions options;
  options.retry_initial_ms = 100;
  options.retry_max_ms = 400;
  ServoCommander commander(servos, mutex, std::move(options), [&now_us] { return now_us; });
  now_us += 1'000'000;
  commander.Command({2.0, 0.0});
  fake->Disconnect();
  fake->Hold();
  commander.Command({2.0, 0.0});  // fails: out
  ASSERT_TRUE(commander.out());
  now_us += 100'000;
  commander.Command({2.0, 0.0});  // starts the reopen, which now waits inside Open
  fake->WaitUntilOpening();
  // The loop goes on meanwhile: commands return at once with the held angles.
  for (int i = 0; i < 10; ++i) {
    now_us += 33'000;
    EXPECT_DOUBLE_EQ(commander.Command({3.0, 0.0}).pan_deg, 2.0);
  }
  EXPECT_TRUE(commander.out());
  fake->Release();
  while (commander.out()) {
    now_us += 33'000;
    commander.Command({3.0, 0.0});
    std::this_thread::yield();
  }
  EXPECT_EQ(commander.counters().recoveries, 1U);
}

TEST(ServoCommanderTest, NonFiniteTargetIsRefusedWithoutAnOutage) {
  Rig rig;
  rig.AdvanceMs(1000);
  rig.commander->Command({std::numeric_limits<double>::quiet_NaN(), 0.0});
  EXPECT_FALSE(rig.commander->out());
  EXPECT_EQ(rig.commander->counters().errors, 1U);
  EXPECT_EQ(rig.commander->counters().outages, 0U);
}

}  // namespace
}  // namespace kapfix::agent
