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

// With a boot id, the sequence starting again is not a restart (e.g. a stream reset): only a
// different boot id is.
TEST(SessionTracker, SameBootIdWithTheSequenceStartingAgainIsTheSameSession) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  client.setBootId(0x1234);
  for (int i = 1; i <= 5; ++i) client.publish(MakeTelemetry(i, 0, 0, 1'000'000 + i * 33'000));
  client.restartAgent(0x1234);
  client.publish(MakeTelemetry(1, 0, 0, 2'000'000));
  EXPECT_EQ(tracker.session(), 1);
  EXPECT_EQ(tracker.restarts(), 0);
  EXPECT_EQ(tracker.bootId(), 0x1234U);
}

TEST(SessionTracker, ADifferentBootIdIsARestartEvenWhileTheSequenceGoesOn) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  bool was_restart = false;
  QObject::connect(&tracker, &SessionTracker::sessionStarted,
                   [&](int /*session*/, bool restart) { was_restart = restart; });
  client.setBootId(0x1234);
  for (int i = 1; i <= 5; ++i) client.publish(MakeTelemetry(i, 0, 0, 1'000'000 + i * 33'000));
  client.setBootId(0x5678);  // the fake's sequence keeps counting up
  client.publish(MakeTelemetry(6, 0, 0, 2'000'000));
  EXPECT_EQ(tracker.session(), 2);
  EXPECT_EQ(tracker.restarts(), 1);
  EXPECT_TRUE(was_restart);
}

// The agent's state carries the boot id too: a restarted agent that publishes its state
// before its first frame is a new session at once.
TEST(SessionTracker, AStateWithANewBootIdIsARestart) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  client.setBootId(7);
  client.publish(MakeTelemetry(1, 0, 0, 1'000'000));
  client.restartAgent(8);
  client.publish(kapfix::v1::AgentState());
  EXPECT_EQ(tracker.session(), 2);
  EXPECT_EQ(tracker.restarts(), 1);
}

// The state inside a reply to request_state may come without a stamped header: it is not
// another agent.
TEST(SessionTracker, AStateWithoutBootIdOrAgentIdIsNotARestart) {
  FakeAgentClient client;
  SessionTracker tracker(client);
  client.setBootId(7);
  client.publish(MakeTelemetry(1, 0, 0, 1'000'000));
  kapfix::v1::Command request;
  request.mutable_request_state();
  client.sendCommand(request);  // the fake replies with an unstamped AgentState
  testing::ProcessEvents();
  client.publish(MakeTelemetry(2, 0, 0, 1'033'000));
  EXPECT_EQ(tracker.session(), 1);
  EXPECT_EQ(tracker.restarts(), 0);
}

}  // namespace
}  // namespace kapfix::station
