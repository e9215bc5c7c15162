#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "kapfix/v1/envelope_codec.hpp"

namespace kapfix::v1 {
namespace {

using ::testing::HasSubstr;

TEST(SequenceGuardTest, AcceptsIncreasingSequenceNumbers) {
  SequenceGuard guard;
  std::string error;
  EXPECT_TRUE(guard.Accept("station", 1, &error)) << error;
  EXPECT_TRUE(guard.Accept("station", 2, &error)) << error;
  EXPECT_TRUE(guard.Accept("station", 10, &error)) << error;  // gaps are lost messages, fine
  EXPECT_EQ(guard.LastAccepted("station"), 10U);
}

TEST(SequenceGuardTest, RefusesAReplayedSequenceNumber) {
  SequenceGuard guard;
  std::string error;
  ASSERT_TRUE(guard.Accept("station", 5, &error));
  EXPECT_FALSE(guard.Accept("station", 5, &error));
  EXPECT_THAT(error, HasSubstr("replayed sequence number 5 from 'station'"));
}

TEST(SequenceGuardTest, RefusesAStaleSequenceNumber) {
  SequenceGuard guard;
  std::string error;
  ASSERT_TRUE(guard.Accept("station", 5, &error));
  EXPECT_FALSE(guard.Accept("station", 4, &error));
  EXPECT_THAT(error, HasSubstr("stale sequence number 4 from 'station': 5 was already accepted"));
}

TEST(SequenceGuardTest, RefusesTheUnsetSequenceNumberZero) {
  SequenceGuard guard;
  std::string error;
  EXPECT_FALSE(guard.Accept("station", 0, &error));
  EXPECT_THAT(error, HasSubstr("sequence number 0 (unset)"));
  EXPECT_EQ(guard.LastAccepted("station"), std::nullopt);
}

TEST(SequenceGuardTest, ARefusalDoesNotMoveTheLastAcceptedNumber) {
  SequenceGuard guard;
  std::string error;
  ASSERT_TRUE(guard.Accept("station", 5, &error));
  ASSERT_FALSE(guard.Accept("station", 3, &error));
  EXPECT_EQ(guard.LastAccepted("station"), 5U);
  EXPECT_TRUE(guard.Accept("station", 6, &error)) << error;
}

TEST(SequenceGuardTest, TracksEachSenderSeparately) {
  SequenceGuard guard;
  std::string error;
  ASSERT_TRUE(guard.Accept("laptop", 100, &error));
  EXPECT_TRUE(guard.Accept("tablet", 1, &error)) << error;
  EXPECT_FALSE(guard.Accept("tablet", 1, &error));
  EXPECT_TRUE(guard.Accept("laptop", 101, &error)) << error;
}

TEST(SequenceGuardTest, ForgetLetsASenderStartItsNumberingAgain) {
  SequenceGuard guard;
  std::string error;
  ASSERT_TRUE(guard.Accept("station", 50, &error));
  guard.Forget("station");
  EXPECT_TRUE(guard.Accept("station", 1, &error)) << error;
}

TEST(SequenceGuardTest, ForgetsTheLeastRecentlyHeardSenderBeyondCapacity) {
  SequenceGuard guard(2);
  std::string error;
  ASSERT_TRUE(guard.Accept("a", 1, &error));
  ASSERT_TRUE(guard.Accept("b", 1, &error));
  ASSERT_TRUE(guard.Accept("a", 2, &error));  // b is now the least recently heard
  ASSERT_TRUE(guard.Accept("c", 1, &error));
  EXPECT_EQ(guard.sender_count(), 2U);
  EXPECT_EQ(guard.LastAccepted("b"), std::nullopt);
  EXPECT_EQ(guard.LastAccepted("a"), 2U);
  EXPECT_EQ(guard.LastAccepted("c"), 1U);
}

TEST(SequenceGuardTest, NamesABinarySenderPrintably) {
  SequenceGuard guard;
  std::string error;
  const std::string routing_id("\0\x01Z", 3);  // ZeroMQ routing ids are binary
  ASSERT_TRUE(guard.Accept(routing_id, 2, &error));
  EXPECT_FALSE(guard.Accept(routing_id, 1, &error));
  EXPECT_THAT(error, HasSubstr("from '\\x00\\x01Z'"));
}

}  // namespace
}  // namespace kapfix::v1
