// The watchdog on a clock the test moves: a stall is a full timeout without a Kick, counted
// once until the next Kick; nothing before the first Kick or while disarmed.
#include "agent/pipeline/watchdog.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>

#include "tests/agent/support/manual_clock.hpp"

namespace kapfix::agent {
namespace {

using std::chrono::milliseconds;
using testing::ManualClock;

constexpr milliseconds kTimeout{100};

struct Rig {
  ManualClock clock;
  std::atomic<int> stalls{0};
  Watchdog watchdog{kTimeout, [this] { ++stalls; }, clock.AsFunction()};
};

TEST(WatchdogTest, AFullTimeoutWithoutAKickIsOneStall) {
  Rig rig;
  rig.watchdog.Kick();
  rig.clock.Advance(kTimeout);
  rig.watchdog.Check();
  EXPECT_EQ(rig.stalls.load(), 1);
  EXPECT_EQ(rig.watchdog.stall_count(), 1u);
}

TEST(WatchdogTest, NoStallJustBeforeTheTimeout) {
  Rig rig;
  rig.watchdog.Kick();
  rig.clock.Advance(kTimeout - milliseconds(1));
  rig.watchdog.Check();
  EXPECT_EQ(rig.watchdog.stall_count(), 0u);
}

TEST(WatchdogTest, AKickPutsTheDeadlineOff) {
  Rig rig;
  rig.watchdog.Kick();
  rig.clock.Advance(kTimeout - milliseconds(1));
  rig.watchdog.Kick();
  rig.clock.Advance(kTimeout - milliseconds(1));
  rig.watchdog.Check();
  EXPECT_EQ(rig.watchdog.stall_count(), 0u);
  rig.clock.Advance(milliseconds(1));
  rig.watchdog.Check();
  EXPECT_EQ(rig.watchdog.stall_count(), 1u);
}

TEST(WatchdogTest, ALongStallCountsOnceUntilTheNextKick) {
  Rig rig;
  rig.watchdog.Kick();
  for (int i = 0; i < 5; ++i) {
    rig.clock.Advance(kTimeout);
    rig.watchdog.Check();
  }
  EXPECT_EQ(rig.watchdog.stall_count(), 1u);
  rig.watchdog.Kick();
  rig.clock.Advance(kTimeout);
  rig.watchdog.Check();
  EXPECT_EQ(rig.watchdog.stall_count(), 2u);
}

TEST(WatchdogTest, NothingIsCountedBeforeTheFirstKick) {
  Rig rig;
  rig.clock.Advance(kTimeout * 10);
  rig.watchdog.Check();
  EXPECT_EQ(rig.watchdog.stall_count(), 0u);
}

TEST(WatchdogTest, NothingIsCountedWhileDisarmed) {
  Rig rig;
  rig.watchdog.Kick();
  rig.watchdog.Disarm();
  rig.clock.Advance(kTimeout * 10);
  rig.watchdog.Check();
  EXPECT_EQ(rig.watchdog.stall_count(), 0u);
}

// Without any Check from outside: the watchdog's own thread sees the clock past the deadline
// and runs the action on its own.
TEST(WatchdogTest, ItsOwnThreadRunsTheActionWhenTheDeadlinePasses) {
  ManualClock clock;
  std::promise<void> fired;
  Watchdog watchdog(
      milliseconds(10), [&fired] { fired.set_value(); }, clock.AsFunction());
  watchdog.Kick();
  clock.Advance(milliseconds(10));
  // A bound only against a hang: the thread looks at least once per timeout (10 ms).
  ASSERT_EQ(fired.get_future().wait_for(std::chrono::seconds(30)), std::future_status::ready);
  EXPECT_EQ(watchdog.stall_count(), 1u);
}

TEST(WatchdogTest, NoActionAfterStop) {
  Rig rig;
  rig.watchdog.Kick();
  rig.watchdog.Stop();
  rig.clock.Advance(kTimeout * 10);
  rig.watchdog.Check();
  EXPECT_EQ(rig.stalls.load(), 0);
}

TEST(WatchdogTest, ATimeoutOfZeroIsRefused) {
  EXPECT_THROW(Watchdog(milliseconds(0), [] {}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix::agent
