// The one table of which kapfix.v1 type travels under which topic.
#include "link/topic_table.hpp"

#include <gtest/gtest.h>

#include <string>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/header.pb.h"
#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/types.pb.h"
#include "kapfix/v1/video.pb.h"

namespace kapfix::link {
namespace {

using kapfix::v1::Command;
using kapfix::v1::Header;
using kapfix::v1::Log;
using kapfix::v1::Rect;
using kapfix::v1::Telemetry;
using kapfix::v1::VideoFrame;

TEST(TopicTest, TopicForNamesEachStreamType) {
  EXPECT_EQ(TopicFor(Telemetry()), "telemetry");
  EXPECT_EQ(TopicFor(VideoFrame()), "video");
  EXPECT_EQ(TopicFor(Log()), "log");
  EXPECT_EQ(TopicFor(Command()), "command");
}

TEST(TopicTest, TopicForIsEmptyForTypesThatDoNotTravelAlone) {
  EXPECT_EQ(TopicFor(Header()), "");
  EXPECT_EQ(TopicFor(Rect()), "");
}

TEST(TopicTest, NoTopicIsAPrefixOfAnother) {
  // ZeroMQ SUB sockets filter by prefix: subscribing to one topic must not select another.
  for (const std::string& a : Topics()) {
    for (const std::string& b : Topics()) {
      if (a != b) {
        EXPECT_FALSE(b.starts_with(a)) << a << " is a prefix of " << b;
      }
    }
  }
}

TEST(TopicTest, NewMessageForTopicMakesTheTypeThatTravelsUnderIt) {
  ASSERT_EQ(Topics().size(), 11U);
  for (const std::string& topic : Topics()) {
    const auto message = NewMessageForTopic(topic);
    ASSERT_NE(message, nullptr) << topic;
    EXPECT_EQ(TopicFor(*message), topic);
  }
}

TEST(TopicTest, NewMessageForTopicRefusesAnUnknownTopic) {
  EXPECT_EQ(NewMessageForTopic("telemetryx"), nullptr);
  EXPECT_EQ(NewMessageForTopic(""), nullptr);
}

}  // namespace
}  // namespace kapfix::link
