#include "groundstation/status/link_status_bar.hpp"

#include <gtest/gtest.h>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

TEST(LinkStatusBar, ShowsLinkUpWithLatencyAndDownWhenLost) {
  FakeAgentClient client;
  LinkStatusBar bar(client);
  LinkState state;
  state.up = true;
  state.source = QStringLiteral("tcp://kite:5555");
  state.latency_us = 12'300;
  client.setLink(state);
  EXPECT_EQ(bar.linkText(), QStringLiteral("LINK UP"));
  EXPECT_EQ(bar.latencyText(), QStringLiteral("12.3 ms"));
  state.up = false;
  client.setLink(state);
  EXPECT_EQ(bar.linkText(), QStringLiteral("LINK DOWN"));
  EXPECT_EQ(bar.latencyText(), QStringLiteral("— ms"));
}

TEST(LinkStatusBar, RefusedKeyIsNamedAsSuch) {
  FakeAgentClient client;
  LinkStatusBar bar(client);
  LinkState state;
  state.source = QStringLiteral("tcp://kite:5555");
  state.handshake_failure = QStringLiteral("the agent refused this station's key");
  client.setLink(state);
  EXPECT_EQ(bar.linkText(), QStringLiteral("KEY REFUSED"));
}

TEST(LinkStatusBar, ShowsTheAgentsFpsAndModeFromTelemetry) {
  FakeAgentClient client;
  LinkStatusBar bar(client);
  client.publish(testing::MakeTelemetry(1, 0, 0, 1));
  EXPECT_EQ(bar.fpsText(), QStringLiteral("29.5 fps"));
  EXPECT_EQ(bar.modeText(), QStringLiteral("Fixate"));
}

TEST(LinkStatusBar, ReplayIsNamedAsSuch) {
  FakeAgentClient client;
  LinkStatusBar bar(client);
  LinkState state;
  state.replay = true;
  state.up = true;
  client.setLink(state);
  EXPECT_EQ(bar.linkText(), QStringLiteral("REPLAY"));
}

}  // namespace
}  // namespace kapfix::station
