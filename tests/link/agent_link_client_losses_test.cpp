// Issue 15, per-subscriber isolation: a station that falls behind loses its own messages and
// is told, also of the tail of a burst, which no later message shows as a gap.
#include <google/protobuf/unknown_field_set.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <string>
#include <thread>

#include "kapfix/v1/telemetry.pb.h"
#include "link/agent_link_client.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::link::AgentLinkClient;
using kapfix::link::AgentLinkClientOptions;

TEST(AgentLinkClientLossesTest, BurstWhoseTailIsDroppedIsCountedLostAfterTheNextHeartbeat) {
  auto publisher_options = TestPublisherOptions();  // heartbeats every 50 ms
  publisher_options.send_high_water_mark = 2;
  FakeAgent agent(publisher_options);
  AgentLinkClientOptions options;
  options.command_endpoint = agent.command_endpoint;
  options.stream_endpoint = agent.stream_endpoint;
  options.heartbeat_interval = std::chrono::milliseconds(50);
  options.stream_receive_high_water_mark = 2;
  AgentLinkClient client(options);
  // The station's I/O thread stops on frame 0 until the whole burst has been handed to ZeroMQ.
  std::promise<void> release;
  const std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> holding{false};
  std::atomic<std::uint64_t> received{0};
  std::atomic<std::uint64_t> last_frame{0};
  client.OnMessage("telemetry", [&](const google::protobuf::Message& message) {
    const auto& telemetry = static_cast<const kapfix::v1::Telemetry&>(message);
    received.fetch_add(1);
    last_frame.store(telemetry.frame_number());
    if (telemetry.frame_number() == 0) {
      holding.store(true);
      released.wait();
    }
  });
  client.Start();
  ASSERT_TRUE(client.WaitForStreams(kWait));
  ASSERT_TRUE(agent.publisher.Publish(LargeTelemetry(0)));
  ASSERT_TRUE(WaitFor([&] { return holding.load(); }));
  constexpr std::uint64_t kBurst = 300;  // 30 MB: far beyond both queues and the TCP buffers
  for (std::uint64_t frame = 1; frame <= kBurst; ++frame) {
    ASSERT_TRUE(agent.publisher.Publish(LargeTelemetry(frame)));
  }
  // Sent means written to this station's pipe or dropped for it: the losses are decided.
  ASSERT_TRUE(WaitFor([&] { return agent.publisher.counters().telemetry_sent == kBurst + 1; }));
  release.set_value();
  // Nothing more is published on "telemetry": every message of the burst is either received or,
  // once a heartbeat sent after the burst has arrived, counted lost.
  EXPECT_TRUE(WaitFor([&] {
    return received.load() + client.SequenceGaps("telemetry") == kBurst + 1;
  })) << received.load()
      << " received, " << client.SequenceGaps("telemetry") << " counted lost";
  // The case a gap can never show: the burst's last message was dropped.
  EXPECT_LT(last_frame.load(), kBurst);
  EXPECT_GE(client.SequenceGaps("telemetry"), kBurst - last_frame.load());
  EXPECT_EQ(client.Status().sequence_gaps, client.SequenceGaps("telemetry"));
  client.Stop();
}

}  // namespace
}  // namespace kapfix::testing
