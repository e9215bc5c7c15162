#include "agent/server/stream_publisher.hpp"

#include <google/protobuf/unknown_field_set.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "kapfix/v1/heartbeat.pb.h"
#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::agent::StreamPublisher;

kapfix::v1::Telemetry TelemetryOfFrame(std::uint64_t frame) {
  kapfix::v1::Telemetry telemetry;
  telemetry.set_frame_number(frame);
  return telemetry;
}

kapfix::v1::VideoFrame VideoOfFrame(std::uint64_t frame) {
  kapfix::v1::VideoFrame video;
  video.set_frame_number(frame);
  video.set_jpeg(std::string(1000, 'j'));
  return video;
}

TEST(StreamPublisherTest, TelemetryPublishedNTimesArrivesNTimesInOrderWithoutGaps) {
  StreamPublisher publisher(TestPublisherOptions());
  RawSubscriber subscriber(publisher.Start(), {"telemetry"});
  ASSERT_TRUE(subscriber.Ready());
  constexpr std::uint64_t kCount = 500;
  for (std::uint64_t i = 0; i < kCount; ++i) ASSERT_TRUE(publisher.Publish(TelemetryOfFrame(i)));
  for (std::uint64_t i = 0; i < kCount; ++i) {
    const auto bytes = subscriber.Next("telemetry");
    ASSERT_TRUE(bytes.has_value()) << "telemetry " << i << " never arrived";
    kapfix::v1::Telemetry telemetry;
    ASSERT_TRUE(telemetry.ParseFromString(*bytes));
    EXPECT_EQ(telemetry.frame_number(), i);
    EXPECT_EQ(telemetry.header().sequence(), i + 1);
  }
  EXPECT_EQ(publisher.counters().telemetry_sent, kCount);
  EXPECT_EQ(publisher.counters().telemetry_dropped, 0U);
}

TEST(StreamPublisherTest, StampsAgentIdVersionAndSequenceButKeepsTheCaptureTime) {
  StreamPublisher publisher(TestPublisherOptions());
  RawSubscriber subscriber(publisher.Start(), {"telemetry"});
  ASSERT_TRUE(subscriber.Ready());
  kapfix::v1::Telemetry telemetry;
  telemetry.mutable_header()->set_capture_time_us(123456);
  publisher.Publish(telemetry);
  const auto bytes = subscriber.Next("telemetry");
  ASSERT_TRUE(bytes.has_value());
  kapfix::v1::Telemetry received;
  ASSERT_TRUE(received.ParseFromString(*bytes));
  EXPECT_EQ(received.header().capture_time_us(), 123456);
  EXPECT_EQ(received.header().agent_id(), kAgentId);
  EXPECT_EQ(received.header().protocol_version(), kapfix::v1::kProtocolVersion);
  EXPECT_EQ(received.header().sequence(), 1U);
  EXPECT_GT(received.header().send_time_us(), 123456);
}

TEST(StreamPublisherTest, SequencesArePerTopic) {
  StreamPublisher publisher(TestPublisherOptions());
  RawSubscriber subscriber(publisher.Start(), {"telemetry", "log"});
  ASSERT_TRUE(subscriber.Ready());
  publisher.Publish(TelemetryOfFrame(0));
  publisher.Publish(kapfix::v1::Log());
  publisher.Publish(TelemetryOfFrame(1));
  kapfix::v1::Log log;
  ASSERT_TRUE(log.ParseFromString(subscriber.Next("log").value_or("")));
  EXPECT_EQ(log.header().sequence(), 1U);
  // The log was read past the first telemetry; the second one carries sequence 2.
  kapfix::v1::Telemetry telemetry;
  ASSERT_TRUE(telemetry.ParseFromString(subscriber.Next("telemetry").value_or("")));
  EXPECT_EQ(telemetry.header().sequence(), 2U);
}

TEST(StreamPublisherTest, VideoFloodKeepsOnlyTheLatestFrameAndCountsTheDrops) {
  auto options = TestPublisherOptions();
  options.video_min_interval = std::chrono::milliseconds(300);
  StreamPublisher publisher(options);
  RawSubscriber subscriber(publisher.Start(), {"video"});
  ASSERT_TRUE(subscriber.Ready());
  constexpr std::uint64_t kFrames = 100;
  for (std::uint64_t i = 0; i < kFrames; ++i) publisher.Publish(VideoOfFrame(i));
  ASSERT_TRUE(WaitFor([&] {
    const auto counters = publisher.counters();
    return counters.video_sent + counters.video_dropped == kFrames;
  }));
  std::uint64_t last = 0;
  std::uint64_t received = 0;
  while (const auto bytes = subscriber.Next("video", std::chrono::milliseconds(200))) {
    kapfix::v1::VideoFrame frame;
    ASSERT_TRUE(frame.ParseFromString(*bytes));
    if (received > 0) {
      EXPECT_GT(frame.frame_number(), last) << "a stale frame was sent";
    }
    last = frame.frame_number();
    ++received;
  }
  EXPECT_EQ(last, kFrames - 1) << "the latest frame must be sent";
  EXPECT_EQ(received, publisher.counters().video_sent);
  EXPECT_GE(publisher.counters().video_dropped, kFrames - 3);
}

TEST(StreamPublisherTest, FullQueueRefusesTelemetryAndCountsIt) {
  auto options = TestPublisherOptions();
  options.queue_messages = 10;
  StreamPublisher publisher(options);  // not started: nothing drains the queue
  int accepted = 0;
  for (int i = 0; i < 15; ++i) accepted += publisher.Publish(TelemetryOfFrame(i)) ? 1 : 0;
  EXPECT_EQ(accepted, 10);
  EXPECT_EQ(publisher.counters().telemetry_dropped, 5U);
}

TEST(StreamPublisherTest, QueueIsBoundedInBytesToo) {
  auto options = TestPublisherOptions();
  options.queue_bytes = 5000;
  StreamPublisher publisher(options);
  kapfix::v1::Log big;
  big.set_text(std::string(2000, 'l'));
  EXPECT_TRUE(publisher.Publish(big));
  EXPECT_TRUE(publisher.Publish(big));
  EXPECT_FALSE(publisher.Publish(big));
  EXPECT_EQ(publisher.counters().other_dropped, 1U);
}

TEST(StreamPublisherTest, SubscriberThatFallsBehindLosesItsOwnMessagesAndSeesTheGap) {
  // Small high-water marks on both sides and messages far larger than the TCP buffers: the
  // subscriber's own ZeroMQ queue overflows, and what it gets shows the loss as a gap in
  // header.sequence (issue 15, item 6: it is told; nobody else is held back).
  auto options = TestPublisherOptions();
  options.send_high_water_mark = 2;
  StreamPublisher publisher(options);
  RawSubscriber subscriber(publisher.Start(), {"telemetry"}, /*receive_high_water_mark=*/2);
  ASSERT_TRUE(subscriber.Ready());
  constexpr std::uint64_t kCount = 200;
  for (std::uint64_t i = 0; i < kCount; ++i) {
    ASSERT_TRUE(publisher.Publish(LargeTelemetry(i)));
  }
  ASSERT_TRUE(WaitFor([&] { return publisher.counters().telemetry_sent == kCount; }));
  // The burst's losses are its tail (a full queue refuses the newest), so the gap shows in the
  // first message sent after the subscriber has caught up. A marker is published until one
  // arrives: one sent while the queue is still full is lost like the rest.
  std::uint64_t received_count = 0;
  std::uint64_t last_sequence = 0;
  bool gap_seen = false;
  bool marker_seen = false;
  for (std::uint64_t marker = kCount; !marker_seen && marker < kCount + 100; ++marker) {
    ASSERT_TRUE(publisher.Publish(TelemetryOfFrame(marker)));
    while (const auto bytes = subscriber.Next("telemetry", std::chrono::milliseconds(200))) {
      kapfix::v1::Telemetry received;
      ASSERT_TRUE(received.ParseFromString(*bytes));
      if (last_sequence != 0 && received.header().sequence() > last_sequence + 1) gap_seen = true;
      last_sequence = received.header().sequence();
      marker_seen = marker_seen || received.frame_number() >= kCount;
      if (received.frame_number() < kCount) ++received_count;
    }
  }
  ASSERT_TRUE(marker_seen) << "no message arrived after the subscriber caught up";
  EXPECT_LT(received_count, kCount);
  EXPECT_TRUE(gap_seen);
}

// Issue 15, item 6: a subscriber that keeps its connection alive but never reads held every
// station's telemetry back for 43 s (XPUB_NODROP). Each telemetry message must reach the
// reading station while the stalled one's queue is full of large messages.
TEST(StreamPublisherTest, StalledSubscriberDoesNotHoldBackAnotherStationsTelemetry) {
  auto options = TestPublisherOptions();
  options.send_high_water_mark = 100;
  StreamPublisher publisher(options);
  const std::string endpoint = publisher.Start();
  RawSubscriber stalled(endpoint, {"log"}, /*receive_high_water_mark=*/1);
  RawSubscriber reader(endpoint, {"telemetry"});
  ASSERT_TRUE(stalled.Ready());  // reads one heartbeat, then never again
  ASSERT_TRUE(reader.Ready());
  // 40 MB of log lines for the stalled one: far beyond its queue and the TCP buffers.
  constexpr std::uint64_t kRounds = 2000;
  std::chrono::microseconds worst{0};
  std::uint64_t missed = 0;       // rounds whose telemetry did not come within 500 ms
  std::uint64_t consecutive = 0;  // of them in a row: the stream stopped
  for (std::uint64_t i = 0; i < kRounds; ++i) {
    kapfix::v1::Log line;
    line.set_text(std::string(20'000, 'l'));
    ASSERT_TRUE(publisher.Publish(line));
    const auto sent = std::chrono::steady_clock::now();
    ASSERT_TRUE(publisher.Publish(TelemetryOfFrame(i)));
    const auto bytes = reader.Next("telemetry", std::chrono::milliseconds(500));
    if (!bytes) {
      ++missed;
      ASSERT_LT(++consecutive, 5U)
          << "telemetry stopped at " << i << "; sent " << publisher.counters().telemetry_sent;
      continue;
    }
    consecutive = 0;
    worst = std::max(worst, std::chrono::duration_cast<std::chrono::microseconds>(
                                std::chrono::steady_clock::now() - sent));
    kapfix::v1::Telemetry received;
    ASSERT_TRUE(received.ParseFromString(*bytes));
    EXPECT_LE(received.frame_number(), i);
  }
  // libzmq occasionally drops one for the reading station too (its own queue's accounting
  // lags its reads); a stalled subscriber used to stop the stream for good.
  EXPECT_LE(missed, kRounds / 100);
  // A figure, not a check (timing on a loaded machine): the target is under 100 ms.
  std::printf("behind a stalled subscriber: slowest telemetry %.1f ms, %llu of %llu missed\n",
              static_cast<double>(worst.count()) / 1000.0, static_cast<unsigned long long>(missed),
              static_cast<unsigned long long>(kRounds));
}

TEST(StreamPublisherTest, HeartbeatsArriveEveryInterval) {
  StreamPublisher publisher(TestPublisherOptions());
  RawSubscriber subscriber(publisher.Start(), {});
  ASSERT_TRUE(subscriber.Ready());
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t previous = 0;
  for (int i = 0; i < 4; ++i) {
    kapfix::v1::Heartbeat heartbeat;
    ASSERT_TRUE(heartbeat.ParseFromString(subscriber.Next("heartbeat").value_or("")));
    EXPECT_EQ(heartbeat.interval_ms(), 50U);
    EXPECT_GT(heartbeat.header().sequence(), previous);
    previous = heartbeat.header().sequence();
  }
  // Four heartbeats at 50 ms: about 150-200 ms, far from the 3 s wait.
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(1000));
}

TEST(StreamPublisherTest, MessageWithoutATopicIsRejected) {
  StreamPublisher publisher(TestPublisherOptions());
  EXPECT_FALSE(publisher.Publish(kapfix::v1::Header()));
  EXPECT_EQ(publisher.counters().rejected, 1U);
}

TEST(StreamPublisherTest, StopReturnsPromptlyWithMessagesQueued) {
  StreamPublisher publisher(TestPublisherOptions());
  publisher.Start();
  for (int i = 0; i < 1000; ++i) publisher.Publish(TelemetryOfFrame(i));
  const auto start = std::chrono::steady_clock::now();
  publisher.Stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(500));
}

}  // namespace
}  // namespace kapfix::testing
