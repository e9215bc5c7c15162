#include "groundstation/client/link_resync.hpp"

#include <gtest/gtest.h>

#include "groundstation/client/fake_agent_client.hpp"

namespace kapfix::station {
namespace {

LinkState Up(bool up) {
  LinkState state;
  state.up = up;
  state.source = QStringLiteral("tcp://agent:5555");
  return state;
}

TEST(LinkResync, LinkComingBackAsksForStateAndPhotosSinceTheNewestHeld) {
  FakeAgentClient client;
  const LinkResync resync(client, 1'000);
  client.setLink(Up(true));
  kapfix::v1::Photo chunk;
  chunk.mutable_metadata()->set_file_name("p.png");
  chunk.mutable_metadata()->set_capture_time_us(5'000'000);
  client.publish(chunk);
  client.setLink(Up(false));
  client.setLink(Up(true));

  ASSERT_EQ(client.commands().size(), 2U);
  const auto& request = client.commands().back().request_state();
  EXPECT_EQ(request.resend_photos_since_us(), 5'000'001);
  EXPECT_TRUE(request.resend_slice_report());
}

TEST(LinkResync, FirstConnectionAsksForPhotosSinceTheStationStarted) {
  FakeAgentClient client;
  const LinkResync resync(client, 777);
  client.setLink(Up(true));
  ASSERT_EQ(client.commands().size(), 1U);
  EXPECT_EQ(client.commands()[0].request_state().resend_photos_since_us(), 777);
}

TEST(LinkResync, LinkStayingUpAsksNothingMore) {
  FakeAgentClient client;
  const LinkResync resync(client, 0);
  LinkState state = Up(true);
  client.setLink(state);
  state.latency_us = 900;  // a new latency is another linkChanged, not a reconnection
  client.setLink(state);
  EXPECT_EQ(client.commands().size(), 1U);
}

}  // namespace
}  // namespace kapfix::station
