#include "agent/downlink/log_publisher.hpp"

#include <gtest/gtest.h>
#include <spdlog/logger.h>

#include <memory>

#include "tests/agent/support/recording_stream_sink.hpp"

namespace kapfix::agent {
namespace {

using testing::RecordingStreamSink;

// A StreamSink that logs while publishing, as a link that reports its own trouble might.
class LoggingSink : public StreamSink {
 public:
  std::shared_ptr<spdlog::logger> logger;
  int published = 0;
  bool Publish(const google::protobuf::Message& /*message*/) override {
    ++published;
    logger->warn("queue full");
    return true;
  }
};

TEST(LogPublisherTest, ALoggedLineIsPublishedWithItsLevelTextAndLogger) {
  RecordingStreamSink sink;
  auto publisher = std::make_shared<LogPublisher>(sink);
  spdlog::logger logger("capture", publisher);
  logger.error("camera lost: {}", "unplugged");
  const auto lines = sink.Messages<kapfix::v1::Log>();
  ASSERT_EQ(lines.size(), 1U);
  EXPECT_EQ(lines[0].level(), kapfix::v1::LOG_LEVEL_ERROR);
  EXPECT_EQ(lines[0].text(), "camera lost: unplugged");
  EXPECT_EQ(lines[0].logger(), "capture");
  EXPECT_GT(lines[0].header().capture_time_us(), 0);
}

TEST(LogPublisherTest, LinesBelowTheLevelStayLocal) {
  RecordingStreamSink sink;
  auto publisher = std::make_shared<LogPublisher>(sink, spdlog::level::warn);
  spdlog::logger logger("agent", publisher);
  logger.set_level(spdlog::level::trace);
  logger.info("mode fixate");
  logger.warn("photo dropped");
  const auto lines = sink.Messages<kapfix::v1::Log>();
  ASSERT_EQ(lines.size(), 1U);
  EXPECT_EQ(lines[0].text(), "photo dropped");
}

TEST(LogPublisherTest, ALineLoggedWhilePublishingIsNotPublishedAgain) {
  LoggingSink sink;
  auto publisher = std::make_shared<LogPublisher>(sink);
  // The logger writes to the publisher; the publisher's sink logs through another logger that
  // also writes to the publisher: without the guard this would recurse.
  auto inner = std::make_shared<spdlog::logger>("link", publisher);
  sink.logger = inner;
  spdlog::logger logger("agent", publisher);
  logger.info("photo saved");
  EXPECT_EQ(sink.published, 1);
}

// Issue 15, item 11: 2,000 refused handshakes were 2,000 Log messages to the station. The
// limit is global: whatever the logger or text, a burst is cut at the bucket's size.
TEST(LogPublisherTest, AFloodOfLinesIsCutAtTheBurstWhateverTheirSource) {
  RecordingStreamSink sink;
  auto publisher = std::make_shared<LogPublisher>(sink, spdlog::level::info,
                                                  LogRateLimit{.burst = 20, .lines_per_s = 1});
  spdlog::logger zap("zap", publisher);
  spdlog::logger server("server", publisher);
  for (int i = 0; i < 1000; ++i) {
    (i % 2 == 0 ? zap : server).warn("refused a connection from key {}", i);
  }
  const std::size_t sent = sink.Messages<kapfix::v1::Log>().size();
  EXPECT_GE(sent, 20U);
  EXPECT_LE(sent, 25U);  // a few refills while the loop runs on a slow machine
}

TEST(LogPublisherTest, EverySpdlogLevelHasAProtoLevel) {
  for (const auto level : {spdlog::level::trace, spdlog::level::debug, spdlog::level::info,
                           spdlog::level::warn, spdlog::level::err, spdlog::level::critical}) {
    EXPECT_NE(LogPublisher::ToProto(level), kapfix::v1::LOG_LEVEL_UNSPECIFIED);
  }
}

}  // namespace
}  // namespace kapfix::agent
