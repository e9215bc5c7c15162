#include "link/stream_loss_counter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace kapfix::link {
namespace {

constexpr std::uint64_t kBoot = 77;

kapfix::v1::Header HeaderOf(std::uint64_t sequence, std::uint64_t boot_id = kBoot) {
  kapfix::v1::Header header;
  header.set_sequence(sequence);
  header.set_boot_id(boot_id);
  return header;
}

kapfix::v1::Heartbeat NewestIs(const std::string& topic, std::uint64_t newest,
                               std::uint64_t boot_id = kBoot) {
  kapfix::v1::Heartbeat heartbeat;
  heartbeat.mutable_header()->set_boot_id(boot_id);
  kapfix::v1::TopicCount* count = heartbeat.add_newest_sequence();
  count->set_topic(topic);
  count->set_count(newest);
  return heartbeat;
}

TEST(StreamLossCounterTest, GapInTheSequenceCountsTheMissingMessages) {
  StreamLossCounter losses;
  EXPECT_EQ(losses.Received("telemetry", HeaderOf(1)), 0U);
  EXPECT_EQ(losses.Received("telemetry", HeaderOf(5)), 3U);
  EXPECT_EQ(losses.Lost("telemetry"), 3U);
  EXPECT_EQ(losses.total(), 3U);
}

TEST(StreamLossCounterTest, HeartbeatNamingANewerSequenceCountsTheTailOnce) {
  StreamLossCounter losses;
  losses.Received("telemetry", HeaderOf(10));
  EXPECT_EQ(losses.Heard(NewestIs("telemetry", 14)), 4U);  // 11..14 never came
  // The next message follows the counted tail: no second count for the same messages.
  EXPECT_EQ(losses.Received("telemetry", HeaderOf(15)), 0U);
  EXPECT_EQ(losses.Heard(NewestIs("telemetry", 15)), 0U);
  EXPECT_EQ(losses.Lost("telemetry"), 4U);
}

TEST(StreamLossCounterTest, TopicNeverReceivedCountsNothingFromAHeartbeat) {
  // Its messages may all have been published before the subscription took effect.
  StreamLossCounter losses;
  losses.Received("log", HeaderOf(3));
  EXPECT_EQ(losses.Heard(NewestIs("telemetry", 500)), 0U);
  EXPECT_EQ(losses.total(), 0U);
}

TEST(StreamLossCounterTest, RestartedAgentStartsTheTopicOver) {
  StreamLossCounter losses;
  losses.Received("telemetry", HeaderOf(900));
  // A new boot numbering from 1 past its predecessor's count: not a loss.
  EXPECT_EQ(losses.Heard(NewestIs("telemetry", 950, kBoot + 1)), 0U);
  EXPECT_EQ(losses.Received("telemetry", HeaderOf(1000, kBoot + 1)), 0U);
  EXPECT_EQ(losses.Received("telemetry", HeaderOf(1002, kBoot + 1)), 1U);
  EXPECT_EQ(losses.total(), 1U);
}

TEST(StreamLossCounterTest, HeartbeatCarriesTheLossesOfEveryTopicThatLostSome) {
  StreamLossCounter losses;
  losses.Received("telemetry", HeaderOf(1));
  losses.Received("telemetry", HeaderOf(3));
  losses.Received("log", HeaderOf(1));
  losses.Heard(NewestIs("log", 4));
  kapfix::v1::Heartbeat mine;
  losses.FillLost(&mine);
  ASSERT_EQ(mine.lost_size(), 2);
  EXPECT_EQ(mine.lost(0).topic(), "log");
  EXPECT_EQ(mine.lost(0).count(), 3U);
  EXPECT_EQ(mine.lost(1).topic(), "telemetry");
  EXPECT_EQ(mine.lost(1).count(), 1U);
}

}  // namespace
}  // namespace kapfix::link
