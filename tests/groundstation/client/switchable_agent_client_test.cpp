#include "groundstation/client/switchable_agent_client.hpp"

#include <gtest/gtest.h>

#include <QSignalSpy>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeTelemetry;

TEST(SwitchableAgentClient, ForwardsOnlyTheCurrentSource) {
  FakeAgentClient live;
  FakeAgentClient replay;
  SwitchableAgentClient views(live);
  QSignalSpy telemetry(&views, &AgentClient::telemetryReceived);
  live.publish(MakeTelemetry(1, 0, 0, 1));
  views.setSource(replay);
  live.publish(MakeTelemetry(2, 0, 0, 2));
  replay.publish(MakeTelemetry(3, 0, 0, 3));
  ASSERT_EQ(telemetry.count(), 2);
  EXPECT_EQ(telemetry.at(1).at(0).value<kapfix::v1::Telemetry>().frame_number(), 3U);
}

TEST(SwitchableAgentClient, CommandsGoToTheCurrentSource) {
  FakeAgentClient live;
  FakeAgentClient other;
  SwitchableAgentClient views(live);
  views.setSource(other);
  kapfix::v1::Command command;
  command.set_select_slice(2);
  views.sendCommand(command);
  EXPECT_TRUE(live.commands().empty());
  EXPECT_EQ(other.commands().size(), 1U);
}

}  // namespace
}  // namespace kapfix::station
