#include <gtest/gtest.h>

#include <QSignalSpy>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeTelemetry;
using testing::ProcessEvents;

// Reaches the protected decoder, as the live link and the replay do.
class DecodingClient final : public AgentClient {
 public:
  void sendCommand(kapfix::v1::Command /*command*/, ReplyCallback /*done*/) override {}
  LinkState linkState() const override { return {}; }
  bool deliver(std::string_view topic, std::string_view payload) {
    return deliverMessage(topic, payload, 1);
  }
};

TEST(AgentClient, PublishedTelemetryArrivesAsItsSignalAndAsBytesForRecording) {
  FakeAgentClient client;
  QSignalSpy telemetry(&client, &AgentClient::telemetryReceived);
  QSignalSpy bytes(&client, &AgentClient::messageReceived);
  client.publish(MakeTelemetry(42, 5, -3, 1'000'000));
  ASSERT_EQ(telemetry.count(), 1);
  const auto received = telemetry.at(0).at(0).value<kapfix::v1::Telemetry>();
  EXPECT_EQ(received.frame_number(), 42U);
  EXPECT_EQ(received.displacement().y_px(), -3);
  ASSERT_EQ(bytes.count(), 1);
  EXPECT_EQ(bytes.at(0).at(0).toString(), QStringLiteral("telemetry"));
}

TEST(AgentClient, BytesThatDoNotDecodeAreNotDelivered) {
  DecodingClient client;
  QSignalSpy telemetry(&client, &AgentClient::telemetryReceived);
  EXPECT_FALSE(client.deliver("telemetry", "\xff\xff garbage"));
  EXPECT_FALSE(client.deliver("no-such-topic", ""));
  EXPECT_EQ(telemetry.count(), 0);
}

TEST(AgentClient, CommandOutcomeArrivesLaterExactlyOnce) {
  FakeAgentClient client;
  int calls = 0;
  client.sendCommand(kapfix::v1::Command{}, [&calls](const CommandOutcome& outcome) {
    EXPECT_TRUE(outcome.ok);
    ++calls;
  });
  EXPECT_EQ(calls, 0) << "the callback must not run inside sendCommand";
  ProcessEvents();
  EXPECT_EQ(calls, 1);
}

TEST(AgentClient, RefusalCarriesTheAgentsReason) {
  FakeAgentClient client;
  client.refuse(kapfix::v1::Command::kSelectSlice, "slice 12 is outside 1..9");
  CommandOutcome seen;
  kapfix::v1::Command command;
  command.set_select_slice(12);
  client.sendCommand(command, [&seen](const CommandOutcome& outcome) { seen = outcome; });
  ProcessEvents();
  EXPECT_TRUE(seen.answered);
  EXPECT_FALSE(seen.ok);
  EXPECT_EQ(seen.reason, QStringLiteral("slice 12 is outside 1..9"));
}

TEST(AgentClient, ReplyWithStateIsAlsoAnnouncedAsState) {
  FakeAgentClient client;
  kapfix::v1::AgentState state;
  state.set_mode(kapfix::v1::MODE_SSP);
  client.setAgentState(state);
  QSignalSpy states(&client, &AgentClient::stateReceived);
  kapfix::v1::Command command;
  command.mutable_request_state();
  client.sendCommand(command);
  ProcessEvents();
  ASSERT_EQ(states.count(), 1);
  EXPECT_EQ(states.at(0).at(0).value<kapfix::v1::AgentState>().mode(), kapfix::v1::MODE_SSP);
}

}  // namespace
}  // namespace kapfix::station
