// The per-station and shared command rates (issue 15): token buckets with time passed in.
#include "agent/server/command_rate_limit.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

using ::testing::HasSubstr;
using Clock = CommandRateLimit::Clock;
using std::chrono::milliseconds;

CommandRateLimitOptions Options(double station_per_s, double station_burst, double all_per_s,
                                double all_burst) {
  CommandRateLimitOptions options;
  options.station_per_s = station_per_s;
  options.station_burst = station_burst;
  options.all_per_s = all_per_s;
  options.all_burst = all_burst;
  return options;
}

// [count] commands `station` gets through at `now`, sent one after another until refused.
int TakenUntilRefused(CommandRateLimit& limit, const std::string& station, Clock::time_point now) {
  int taken = 0;
  while (limit.Take(station, now).allowed) ++taken;
  return taken;
}

TEST(CommandRateLimitTest, StationGetsItsBurstThenARefusalNamingItsRate) {
  CommandRateLimit limit(Options(20, 40, 1000, 2000));
  const Clock::time_point now{};
  EXPECT_EQ(TakenUntilRefused(limit, "a", now), 40);
  const CommandRateLimit::Decision refused = limit.Take("a", now);
  EXPECT_FALSE(refused.allowed);
  EXPECT_THAT(refused.reason, HasSubstr("rate limited: at most 20 commands/s per station"));
}

TEST(CommandRateLimitTest, RefusalSaysWhenTheNextTokenComes) {
  CommandRateLimit limit(Options(20, 1, 1000, 2000));
  const Clock::time_point now{};
  ASSERT_TRUE(limit.Take("a", now).allowed);
  const CommandRateLimit::Decision refused = limit.Take("a", now);
  ASSERT_FALSE(refused.allowed);
  EXPECT_EQ(std::chrono::duration_cast<milliseconds>(refused.retry_at - now), milliseconds(50));
  EXPECT_TRUE(limit.Take("a", refused.retry_at).allowed);
}

TEST(CommandRateLimitTest, StationRefillsAtItsRateUpToItsBurst) {
  CommandRateLimit limit(Options(20, 40, 1000, 2000));
  const Clock::time_point start{};
  ASSERT_EQ(TakenUntilRefused(limit, "a", start), 40);
  EXPECT_EQ(TakenUntilRefused(limit, "a", start + milliseconds(500)), 10);     // 20/s × 0.5 s
  EXPECT_EQ(TakenUntilRefused(limit, "a", start + milliseconds(60'000)), 40);  // not 1,200
}

TEST(CommandRateLimitTest, OneStationOverItsRateLeavesAnotherItsOwnBurst) {
  CommandRateLimit limit(Options(20, 40, 1000, 2000));
  const Clock::time_point now{};
  ASSERT_EQ(TakenUntilRefused(limit, "flooding", now), 40);
  EXPECT_EQ(TakenUntilRefused(limit, "quiet", now), 40);
}

TEST(CommandRateLimitTest, AllStationsTogetherGetNoMoreThanTheSharedBurst) {
  CommandRateLimit limit(Options(20, 40, 100, 200));
  const Clock::time_point now{};
  int taken = 0;
  for (int station = 0; station < 10; ++station) {
    taken += TakenUntilRefused(limit, "station " + std::to_string(station), now);
  }
  EXPECT_EQ(taken, 200);
  const CommandRateLimit::Decision refused = limit.Take("station 9", now);
  EXPECT_THAT(refused.reason, HasSubstr("at most 100 commands/s from all stations together"));
}

TEST(CommandRateLimitTest, SharedRefusalHoldsTheStationForItsOwnTokenInterval) {
  CommandRateLimit limit(Options(20, 40, 100, 40));
  const Clock::time_point now{};
  ASSERT_EQ(TakenUntilRefused(limit, "a", now), 40);
  const CommandRateLimit::Decision refused = limit.Take("b", now);
  ASSERT_FALSE(refused.allowed);
  // The shared bucket has a token in 10 ms, but "b" is not asked back before its own 50 ms.
  EXPECT_EQ(std::chrono::duration_cast<milliseconds>(refused.retry_at - now), milliseconds(50));
}

TEST(CommandRateLimitTest, ARefusedCommandTakesNoTokenFromTheSharedBucket) {
  CommandRateLimit limit(Options(1, 2, 1, 3));
  const Clock::time_point now{};
  ASSERT_EQ(TakenUntilRefused(limit, "a", now), 2);
  for (int i = 0; i < 100; ++i) ASSERT_FALSE(limit.Take("a", now).allowed);
  EXPECT_TRUE(limit.Take("b", now).allowed);  // the shared bucket's third token is still there
}

TEST(CommandRateLimitTest, ForgettingFullBucketsKeepsEveryStationsDebt) {
  CommandRateLimitOptions options = Options(1, 2, 1000, 2000);
  options.max_stations = 2;
  CommandRateLimit limit(options);
  const Clock::time_point now{};
  ASSERT_EQ(TakenUntilRefused(limit, "a", now), 2);
  ASSERT_TRUE(limit.Take("b", now).allowed);
  // "c" finds no room and no full bucket to forget: it shares the overflow bucket.
  EXPECT_EQ(TakenUntilRefused(limit, "c", now), 2);
  EXPECT_EQ(limit.stations_tracked(), 2U);
  EXPECT_FALSE(limit.Take("a", now).allowed);  // "a" was not forgotten while in debt
  // 10 s later every bucket is full again: a newcomer makes room by forgetting them.
  const Clock::time_point later = now + milliseconds(10'000);
  EXPECT_EQ(TakenUntilRefused(limit, "d", later), 2);
  EXPECT_LE(limit.stations_tracked(), 2U);
}

TEST(CommandRateLimitOptionsTest, DefaultsAreValid) {
  std::string why;
  EXPECT_TRUE(CommandRateLimitOptions{}.IsValid(&why)) << why;
}

TEST(CommandRateLimitOptionsTest, TinyRateIsRefusedNamingTheField) {
  std::string why;
  EXPECT_FALSE(Options(1e-45, 40, 100, 200).IsValid(&why));
  EXPECT_THAT(why, HasSubstr("station_per_s"));
}

TEST(CommandRateLimitOptionsTest, BurstBelowOneCommandIsRefused) {
  std::string why;
  EXPECT_FALSE(Options(20, 0.5, 100, 200).IsValid(&why));
  EXPECT_THAT(why, HasSubstr("station_burst"));
}

TEST(CommandRateLimitOptionsTest, SharedRateBelowTheStationsIsRefused) {
  std::string why;
  EXPECT_FALSE(Options(20, 40, 10, 200).IsValid(&why));
  EXPECT_THAT(why, HasSubstr("all_per_s"));
}

}  // namespace
}  // namespace kapfix::agent
