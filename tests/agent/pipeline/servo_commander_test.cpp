#include "agent/pipeline/servo_commander.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include "agent/servo/fake_servo_driver.hpp"
#include "agent/worker/work_queue.hpp"
#include "tests/agent/support/gate.hpp"
#include "tests/agent/support/held_open_servo_driver.hpp"

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

// The reopen on a worker, held inside the device's Open until the test releases it.
struct WorkerRig {
  std::int64_t now_us = 0;
  testing::HeldOpenServoDriver* fake = nullptr;
  std::unique_ptr<LimitedServoDriver> servos;
  std::mutex mutex;
  std::shared_ptr<WorkQueue> worker;
  std::vector<DeviceHealth> reports;
  std::unique_ptr<ServoCommander> commander;

  explicit WorkerRig(std::size_t max_jobs = 4)
      : worker(std::make_shared<WorkQueue>("worker", max_jobs)) {
    auto backend = std::make_unique<testing::HeldOpenServoDriver>();
    fake = backend.get();
    servos = std::make_unique<LimitedServoDriver>(
        std::move(backend), ServoLimits{}, ServoLimits{}, [this] { return now_us; }, 1.0);
    EXPECT_TRUE(servos->Open(nullptr));
    ServoCommanderOptions options;
    options.retry_initial_ms = 100;
    options.retry_max_ms = 400;
    options.worker = worker;
    options.on_health = [this](const DeviceHealth& health) { reports.push_back(health); };
    commander = std::make_unique<ServoCommander>(*servos, mutex, std::move(options),
                                                 [this] { return now_us; });
  }
  ~WorkerRig() {
    fake->Release();  // a test that failed half-way must not leave the worker inside Open
    commander.reset();
  }
  void AdvanceMs(int ms) { now_us += std::int64_t{ms} * 1000; }
  // Puts the servos at `pan_deg`, then unplugs the device with its next Open held: out.
  void FailWithOpenHeld(double pan_deg) {
    AdvanceMs(1000);
    commander->Command({pan_deg, 0.0});
    fake->Disconnect();
    fake->Hold();
    commander->Command({pan_deg, 0.0});
  }
};

TEST(ServoCommanderTest, ControlStepsGoOnWhileTheWorkerReopensTheDriver) {
  WorkerRig rig;
  rig.FailWithOpenHeld(2.0);
  ASSERT_TRUE(rig.commander->out());
  rig.AdvanceMs(100);
  rig.commander->Command({2.0, 0.0});  // posts the reopen, which now waits inside Open
  rig.fake->WaitUntilOpening();
  // The loop goes on meanwhile: every command returns at once with the held angles.
  for (int i = 0; i < 10; ++i) {
    rig.AdvanceMs(33);
    EXPECT_DOUBLE_EQ(rig.commander->Command({3.0, 0.0}).pan_deg, 2.0);
  }
  EXPECT_TRUE(rig.commander->out());
  EXPECT_TRUE(rig.fake->opening());
  EXPECT_EQ(rig.commander->counters().recoveries, 0U);
}

TEST(ServoCommanderTest, TheHealthSaysReopeningWhileTheWorkerIsAtIt) {
  WorkerRig rig;
  rig.FailWithOpenHeld(2.0);
  rig.AdvanceMs(100);
  rig.commander->Command({2.0, 0.0});
  rig.fake->WaitUntilOpening();
  ASSERT_EQ(rig.reports.size(), 2U);
  EXPECT_EQ(rig.reports[0].status, DeviceStatus::kLost);
  EXPECT_FALSE(rig.reports[0].reopening());
  EXPECT_EQ(rig.reports[1].status, DeviceStatus::kLost);
  EXPECT_TRUE(rig.reports[1].reopening()) << rig.reports[1].reason;
  EXPECT_NE(rig.reports[1].reason.find(rig.reports[0].reason), std::string::npos)
      << "the reason of the outage is kept: " << rig.reports[1].reason;
  rig.fake->Release();
  rig.worker->Flush();
  rig.AdvanceMs(33);
  rig.commander->Command({2.0, 0.0});
  EXPECT_EQ(rig.reports.back(), DeviceHealth::Ok());
}

TEST(ServoCommanderTest, TheReopenedDriverIsTakenUpAtTheNextCommand) {
  WorkerRig rig;
  rig.FailWithOpenHeld(2.0);
  rig.AdvanceMs(100);
  rig.commander->Command({2.0, 0.0});
  rig.fake->WaitUntilOpening();
  const std::size_t sent = rig.fake->commands().size();
  rig.fake->Release();
  rig.worker->Flush();  // the device is open again; the control thread has not seen it yet
  EXPECT_TRUE(rig.commander->out());
  EXPECT_EQ(rig.fake->commands().size(), sent) << "nothing is sent until the swap";
  rig.AdvanceMs(33);
  rig.commander->Command({3.0, 0.0});  // the frame boundary: taken up, and this command sent
  EXPECT_FALSE(rig.commander->out());
  EXPECT_EQ(rig.commander->counters().recoveries, 1U);
  EXPECT_GT(rig.fake->commands().size(), sent);
  // That first command slews from where the device says the servos stand (no time since the
  // swap: no move); the next frame's target is reached.
  rig.AdvanceMs(100);
  EXPECT_DOUBLE_EQ(rig.commander->Command({3.0, 0.0}).pan_deg, 3.0);
  EXPECT_DOUBLE_EQ(rig.fake->angle(ServoAxis::kPan), 3.0);
}

// The watchdog parks under the same lock: it is refused at once while the device is being
// opened, instead of waiting for the worker.
TEST(ServoCommanderTest, AParkDuringTheReopenIsRefusedWithoutWaitingForTheDevice) {
  WorkerRig rig;
  rig.FailWithOpenHeld(2.0);
  rig.AdvanceMs(100);
  rig.commander->Command({2.0, 0.0});
  rig.fake->WaitUntilOpening();
  const std::size_t sent = rig.fake->commands().size();
  std::string error;
  {
    const std::lock_guard lock(rig.mutex);
    EXPECT_FALSE(rig.servos->Park(&error));
  }
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
  EXPECT_EQ(rig.fake->commands().size(), sent);
  EXPECT_TRUE(rig.fake->opening());
}

// A worker that cannot take the reopen (full): the attempt fails with the queue's reason and
// is retried after the back-off, not lost.
TEST(ServoCommanderTest, AReopenTheWorkerRefusesIsRetriedAfterTheBackOff) {
  testing::Gate disk;  // outlives the rig's worker, which waits on it
  WorkerRig rig(1);
  std::string error;
  // One job running (held), one waiting: the queue is full.
  ASSERT_TRUE(rig.worker->Post(
      "slow write",
      [&disk]() -> WorkQueue::Result {
        disk.Pass();
        return nullptr;
      },
      &error));
  disk.WaitEntered();
  ASSERT_TRUE(rig.worker->Post(
      "next write", [] { return WorkQueue::Result(); }, &error));
  rig.AdvanceMs(1000);
  rig.commander->Command({2.0, 0.0});
  rig.fake->Disconnect();
  rig.commander->Command({2.0, 0.0});  // out
  rig.AdvanceMs(100);
  rig.commander->Command({2.0, 0.0});  // the reopen is refused
  EXPECT_TRUE(rig.commander->out());
  EXPECT_FALSE(rig.reports.back().reopening());
  disk.Open();
  rig.worker->Flush();
  const int opened = rig.fake->open_count();
  rig.AdvanceMs(199);
  rig.commander->Command({2.0, 0.0});  // before the doubled back-off (200 ms): no attempt
  rig.worker->Flush();
  EXPECT_EQ(rig.fake->open_count(), opened) << "retried before the back-off allowed";
  rig.AdvanceMs(1);
  rig.commander->Command({2.0, 0.0});  // posts the reopen
  rig.worker->Flush();
  rig.commander->Command({2.0, 0.0});  // takes it up
  EXPECT_FALSE(rig.commander->out());
  EXPECT_EQ(rig.commander->counters().recoveries, 1U);
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
