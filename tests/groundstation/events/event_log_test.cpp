#include "groundstation/events/event_log.hpp"

#include <gtest/gtest.h>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeSliceReport;
using testing::MakeTelemetry;
using testing::ProcessEvents;

LinkState Link(bool up, std::int64_t latency_us) {
  LinkState state;
  state.up = up;
  state.source = QStringLiteral("tcp://kite:5555");
  state.latency_us = latency_us;
  return state;
}

TEST(EventLog, LinkUpIsLoggedOnceHoweverOftenItsLatencyChanges) {
  FakeAgentClient client;
  EventLog log(client);
  for (int i = 0; i < 10; ++i) client.setLink(Link(true, 1000 + i));
  client.setLink(Link(false, -1));
  client.setLink(Link(true, 900));
  EXPECT_EQ(log.lines(),
            QStringList({QStringLiteral("link up: tcp://kite:5555"), QStringLiteral("link down"),
                         QStringLiteral("link up: tcp://kite:5555")}));
}

TEST(EventLog, ModeChangesAreLoggedNotEveryFrame) {
  FakeAgentClient client;
  EventLog log(client);
  for (int i = 1; i <= 30; ++i) client.publish(MakeTelemetry(i, 0, 0, i * 33'000));
  kapfix::v1::Telemetry idle = MakeTelemetry(31, 0, 0, 31 * 33'000);
  idle.set_mode(kapfix::v1::MODE_IDLE);
  client.publish(idle);
  EXPECT_EQ(log.lines(),
            QStringList({QStringLiteral("mode: Fixate on slice 4"), QStringLiteral("mode: Idle")}));
}

TEST(EventLog, SspResultIsOneReadableLine) {
  FakeAgentClient client;
  EventLog log(client);
  client.publish(MakeSliceReport(9, 6));
  ASSERT_EQ(log.lines().size(), 1);
  EXPECT_EQ(log.lines().front(),
            QStringLiteral("SSP finished: slice 6 recommended (DC 21, FFT 6.00 k) of 9 slices "
                           "after 40 frames"));
}

TEST(EventLog, CommandsAreNotRepeatedButRefusalsAre) {
  FakeAgentClient client;
  EventLog log(client);
  client.refuse(kapfix::v1::Command::kSelectSlice, "slice 12 is outside 1..9");
  kapfix::v1::Command photo;
  photo.mutable_take_photo();
  client.sendCommand(photo);
  kapfix::v1::Command slice;
  slice.set_select_slice(12);
  client.sendCommand(slice);
  ProcessEvents();
  EXPECT_EQ(log.lines(), QStringList({QStringLiteral("refused: slice 12 is outside 1..9")}));
}

TEST(EventLog, AReceivedPhotoIsOneLine) {
  FakeAgentClient client;
  EventLog log(client);
  kapfix::v1::Photo chunk;
  chunk.mutable_metadata()->set_file_name("kapfix_0001.jpg");
  chunk.mutable_metadata()->set_slice(4);
  chunk.mutable_metadata()->set_confidence(0.5F);
  chunk.set_total_bytes(6);
  chunk.set_data("abc");
  client.publish(chunk);  // first half: nothing yet
  chunk.set_offset_bytes(3);
  client.publish(chunk);
  EXPECT_EQ(log.lines(),
            QStringList({QStringLiteral("photo kapfix_0001.jpg (slice 4, confidence 0.50)")}));
}

}  // namespace
}  // namespace kapfix::station
