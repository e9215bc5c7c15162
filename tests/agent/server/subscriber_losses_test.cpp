// Issue 15, per-subscriber isolation, seen from the agent: each station's losses reach the
// command server in its heartbeats, so the agent knows which station falls behind.
#include <google/protobuf/unknown_field_set.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "agent/server/subscriber_loss_book.hpp"
#include "kapfix/v1/telemetry.pb.h"
#include "link/agent_link_client.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::agent::StationLosses;
using kapfix::link::AgentLinkClient;
using kapfix::link::AgentLinkClientOptions;

AgentLinkClientOptions StationOptions(const FakeAgent& agent) {
  AgentLinkClientOptions options;
  options.command_endpoint = agent.command_endpoint;
  options.stream_endpoint = agent.stream_endpoint;
  options.heartbeat_interval = std::chrono::milliseconds(50);
  return options;
}

// How many stations report telemetry lost; `lost` is the last one's count.
std::uint64_t StationsLosingTelemetry(const std::vector<StationLosses>& stations,
                                      std::uint64_t* lost) {
  std::uint64_t count = 0;
  for (const StationLosses& station : stations) {
    const auto it = station.by_topic.find("telemetry");
    if (it == station.by_topic.end() || it->second == 0) continue;
    ++count;
    *lost = it->second;
  }
  return count;
}

TEST(SubscriberLossesTest, AgentCountsTheStalledStationsLossesWhileTheReadingOnesStayZero) {
  auto publisher_options = TestPublisherOptions();
  publisher_options.send_high_water_mark = 50;
  FakeAgent agent(publisher_options);

  AgentLinkClient reader(StationOptions(agent));
  std::atomic<std::uint64_t> read{0};
  reader.OnMessage("telemetry", [&](const google::protobuf::Message&) { read.fetch_add(1); });

  AgentLinkClientOptions slow_options = StationOptions(agent);
  slow_options.stream_receive_high_water_mark = 2;
  AgentLinkClient slow(slow_options);
  std::promise<void> release;
  const std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> holding{false};
  std::atomic<std::uint64_t> slow_read{0};
  slow.OnMessage("telemetry", [&](const google::protobuf::Message& message) {
    slow_read.fetch_add(1);
    if (static_cast<const kapfix::v1::Telemetry&>(message).frame_number() == 0) {
      holding.store(true);
      released.wait();  // stalls this station's I/O thread: it reads nothing meanwhile
    }
  });
  reader.Start();
  slow.Start();
  ASSERT_TRUE(reader.WaitForStreams(kWait));
  ASSERT_TRUE(slow.WaitForStreams(kWait));
  ASSERT_TRUE(agent.publisher.Publish(LargeTelemetry(0)));
  ASSERT_TRUE(WaitFor([&] { return holding.load() && read.load() == 1; }));
  // 300 messages of 100 kB in batches of 10 that the reader has received before the next: the
  // reader never has more than its queue in flight, the stalled one's overflows.
  constexpr std::uint64_t kCount = 301;
  for (std::uint64_t frame = 1; frame < kCount; ++frame) {
    ASSERT_TRUE(agent.publisher.Publish(LargeTelemetry(frame)));
    if (frame % 10 == 0) {
      ASSERT_TRUE(WaitFor([&] { return read.load() == frame + 1; })) << "reader at " << read.load();
    }
  }
  ASSERT_TRUE(WaitFor([&] { return read.load() == kCount; }));
  release.set_value();
  // The stalled station counts what it lost (after the agent's next heartbeat) and reports it
  // in its own next heartbeat; the agent's count then equals the station's.
  std::uint64_t agent_count = 0;
  EXPECT_TRUE(WaitFor([&] {
    const std::uint64_t lost = slow.SequenceGaps("telemetry");
    return slow_read.load() + lost == kCount && lost > 0 &&
           StationsLosingTelemetry(agent.server.SubscriberLosses(), &agent_count) == 1 &&
           agent_count == lost;
  })) << "stalled station: "
      << slow_read.load() << " read, " << slow.SequenceGaps("telemetry")
      << " lost; the agent counts " << agent_count;
  // The reading station: everything arrived, and the agent heard it report nothing lost.
  EXPECT_EQ(read.load(), kCount);
  EXPECT_EQ(reader.Status().sequence_gaps, 0U);
  EXPECT_GE(agent.server.SubscriberLosses().size(), 2U);
  reader.Stop();
  slow.Stop();
}

}  // namespace
}  // namespace kapfix::testing
