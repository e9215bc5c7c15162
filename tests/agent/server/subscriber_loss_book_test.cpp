#include "agent/server/subscriber_loss_book.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace kapfix::agent {
namespace {

using Clock = SubscriberLossBook::Clock;
using std::chrono::seconds;

SubscriberLossBookOptions WithStations(std::size_t stations) {
  SubscriberLossBookOptions options;
  options.max_stations = stations;
  return options;
}

kapfix::v1::Heartbeat Lost(std::uint64_t telemetry, std::uint64_t log = 0) {
  kapfix::v1::Heartbeat heartbeat;
  for (const auto& [topic, count] : {std::pair{"telemetry", telemetry}, std::pair{"log", log}}) {
    if (count == 0) continue;
    kapfix::v1::TopicCount* entry = heartbeat.add_lost();
    entry->set_topic(topic);
    entry->set_count(count);
  }
  return heartbeat;
}

TEST(SubscriberLossBookTest, GrowingLossesGiveANoticeNamingTheStationAtMostOncePerPeriod) {
  SubscriberLossBook book;
  const Clock::time_point t0{};
  EXPECT_EQ(book.Report("kite-tablet", Lost(0), t0), "");
  EXPECT_EQ(book.Report("kite-tablet", Lost(120), t0 + seconds(2)),
            "station kite-tablet lost 120 telemetry messages in the last 2 s: it reads too "
            "slowly or its link is saturated");
  EXPECT_EQ(book.Report("kite-tablet", Lost(300, 4), t0 + seconds(5)), "");  // within 10 s
  EXPECT_EQ(book.Report("kite-tablet", Lost(310, 4), t0 + seconds(12)),
            "station kite-tablet lost 4 log and 190 telemetry messages in the last 10 s: it "
            "reads too slowly or its link is saturated");
  EXPECT_EQ(book.TotalLost("kite-tablet"), 314U);
}

TEST(SubscriberLossBookTest, StationThatLosesNothingIsKeptAtZeroWithoutANotice) {
  SubscriberLossBook book;
  const Clock::time_point t0{};
  for (int i = 0; i < 30; ++i) EXPECT_EQ(book.Report("reader", Lost(0), t0 + seconds(i)), "");
  ASSERT_EQ(book.Stations().size(), 1U);
  EXPECT_EQ(book.Stations()[0].station, "reader");
  EXPECT_EQ(book.TotalLost("reader"), 0U);
}

TEST(SubscriberLossBookTest, RestartedStationsLowerCountIsNewLossesNotANegativeOne) {
  SubscriberLossBook book;
  const Clock::time_point t0{};
  EXPECT_NE(book.Report("ctl", Lost(50), t0), "");
  EXPECT_EQ(book.Report("ctl", Lost(7), t0 + seconds(11)),
            "station ctl lost 7 telemetry messages in the last 11 s: it reads too slowly or its "
            "link is saturated");
}

TEST(SubscriberLossBookTest, TableIsBoundedAndForgetsTheLeastRecentlyHeardStation) {
  SubscriberLossBook book(WithStations(2));
  const Clock::time_point t0{};
  book.Report("a", Lost(1), t0);
  book.Report("b", Lost(2), t0);
  book.Report("a", Lost(3), t0);  // a heard again: b is now the oldest
  book.Report("c", Lost(4), t0);
  ASSERT_EQ(book.Stations().size(), 2U);
  EXPECT_EQ(book.Stations()[0].station, "c");
  EXPECT_EQ(book.Stations()[1].station, "a");
  EXPECT_EQ(book.TotalLost("b"), 0U);
}

TEST(SubscriberLossBookTest, TopicsPerStationAreBounded) {
  SubscriberLossBookOptions options;
  options.max_topics = 1;
  SubscriberLossBook book(options);
  book.Report("a", Lost(5, 6), Clock::time_point{});
  ASSERT_EQ(book.Stations().size(), 1U);
  EXPECT_EQ(book.Stations()[0].by_topic.size(), 1U);
}

TEST(SubscriberLossBookTest, NoStationsIsRefusedNamingTheOption) {
  std::string error;
  EXPECT_FALSE(WithStations(0).IsValid(&error));
  EXPECT_NE(error.find("max_stations"), std::string::npos);
  EXPECT_THROW(SubscriberLossBook(WithStations(0)), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix::agent
