// ReplayWindow (issue 15, item 8): replays across connections, send times outside the agent's
// clock window, and commands from before an agent restart are refused.
#include "agent/server/replay_window.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

constexpr std::int64_t kStart = 1'800'000'000'000'000;  // [µs since epoch] the agent's start
constexpr std::int64_t kSecond = 1'000'000;             // [µs]

TEST(ReplayWindowTest, SameCommandAcceptedOnceWhateverTheConnection) {
  ReplayWindow window({}, kStart);
  std::string error;
  EXPECT_TRUE(window.Accept("laptop", kStart + kSecond, 1, kStart + kSecond, &error)) << error;
  EXPECT_FALSE(window.Accept("laptop", kStart + kSecond, 1, kStart + 2 * kSecond, &error));
  EXPECT_NE(error.find("replayed"), std::string::npos) << error;
}

TEST(ReplayWindowTest, RestartedStationNumberingFromOneAgainIsAccepted) {
  ReplayWindow window({}, kStart);
  EXPECT_TRUE(window.Accept("laptop", kStart + kSecond, 1, kStart + kSecond, nullptr));
  EXPECT_TRUE(window.Accept("laptop", kStart + 3 * kSecond, 1, kStart + 3 * kSecond, nullptr));
}

TEST(ReplayWindowTest, CommandStamped1970IsRefusedNamingTheSkew) {
  ReplayWindow window({}, kStart);
  std::string error;
  EXPECT_FALSE(window.Accept("laptop", 1, 1, kStart + kSecond, &error));
  EXPECT_NE(error.find("behind the agent's clock"), std::string::npos) << error;
}

TEST(ReplayWindowTest, CommandStampedAheadOfTheWindowIsRefusedNamingTheSkew) {
  ReplayWindow window({}, kStart);
  std::string error;
  EXPECT_FALSE(window.Accept("laptop", kStart + 45 * kSecond, 1, kStart + kSecond, &error));
  EXPECT_NE(error.find("44.000 s ahead"), std::string::npos) << error;
}

TEST(ReplayWindowTest, CommandStampedBeforeTheAgentStartedIsRefused) {
  ReplayWindow window({}, kStart);
  std::string error;
  EXPECT_FALSE(window.Accept("laptop", kStart - kSecond, 1, kStart + kSecond, &error));
  EXPECT_NE(error.find("horizon"), std::string::npos) << error;
}

TEST(ReplayWindowTest, HorizonSurvivesARestartWhoseClockCameBackBehind) {
  kapfix::testing::TempDir temp;
  ReplayWindowOptions options;
  options.state_file = temp.path() / "replay_horizon";
  const std::int64_t sent = kStart + 10 * kSecond;
  {
    ReplayWindow first(options, kStart);
    ASSERT_TRUE(first.Accept("laptop", sent, 7, sent, nullptr));
  }
  // The agent restarts with its clock 5 s behind the first run's last command.
  ReplayWindow second(options, sent - 5 * kSecond);
  std::string error;
  EXPECT_FALSE(second.Accept("laptop", sent, 7, sent - 4 * kSecond, &error));
  EXPECT_GE(second.horizon_us(), sent);
}

}  // namespace
}  // namespace kapfix::agent
