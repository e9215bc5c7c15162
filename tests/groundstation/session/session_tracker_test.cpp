#include "groundstation/session/session_tracker.hpp"

#include <gtest/gtest.h>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeTelemetry;

TEST(SessionTracker, FirstAgentHeardIsSessionOneAndNotARestart) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  client.publish(MakeTelemetry(1, 0, 0, 1'000'000));
  client.publish(MakeTelemetry(2, 0, 0, 1'033'000));
  EXPECT_EQ(tracker.session(), 1);
  EXPECT_EQ(tracker.restarts(), 0);
}

TEST(SessionTracker, SequenceStartingAgainIsARestartedAgent) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  int announced = 0;
  bool was_restart = false;
  QObject::connect(&tracker, &SessionTracker::sessionStarted, [&](int session, bool restart) {
    announced = session;
    was_restart = restart;
  });
  for (int i = 1; i <= 5; ++i) client.publish(MakeTelemetry(i, 0, 0, 1'000'000 + i * 33'000));
  client.restartAgent();
  client.publish(MakeTelemetry(1, 0, 0, 9'000'000));
  EXPECT_EQ(tracker.session(), 2);
  EXPECT_EQ(announced, 2);
  EXPECT_TRUE(was_restart);
}

TEST(SessionTracker, LostMessagesAreNotARestart) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  client.publish(MakeTelemetry(1, 0, 0, 1'000'000));
  // The fake numbers all its messages in one sequence: these make the telemetry skip ahead,
  // as lost telemetry would.
  for (int i = 0; i < 3; ++i) client.publish(kapfix::v1::Log());
  client.publish(MakeTelemetry(5, 0, 0, 1'133'000));
  EXPECT_EQ(tracker.session(), 1);
  EXPECT_EQ(tracker.restarts(), 0);
}

}  // namespace
}  // namespace kapfix::station
