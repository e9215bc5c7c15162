#include "kapfix/v1/envelope_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/types.pb.h"

namespace kapfix::v1 {
namespace {

using ::testing::HasSubstr;

Telemetry StampedTelemetry() {
  Telemetry telemetry;
  Stamp(telemetry.mutable_header(), "kite-1", 3);
  telemetry.set_frame_number(1234);
  telemetry.mutable_displacement()->set_x_px(-17);
  telemetry.mutable_displacement()->set_x_subpx(0.25F);
  telemetry.set_mode(MODE_FIXATE);
  return telemetry;
}

// A message whose last field is a long string, so cutting bytes off its end always cuts
// inside a field (a cut at a field boundary would leave a valid, shorter message).
std::string LogBytes() {
  Log log;
  Stamp(log.mutable_header(), "kite-1", 1);
  log.set_level(LOG_LEVEL_WARN);
  log.set_text(std::string(100, 'w'));
  return log.SerializeAsString();
}

TEST(DecodeTest, AcceptsAStampedMessage) {
  const Telemetry sent = StampedTelemetry();
  Telemetry received;
  std::string error;
  ASSERT_TRUE(Decode(sent.SerializeAsString(), &received, kMaxMessageBytes, &error)) << error;
  EXPECT_EQ(received.frame_number(), 1234U);
  EXPECT_EQ(received.displacement().x_px(), -17);
  EXPECT_EQ(received.header().agent_id(), "kite-1");
}

TEST(DecodeTest, RejectsTruncatedBytes) {
  const std::string bytes = LogBytes();
  Log log;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(Decode(std::string_view(bytes).substr(0, bytes.size() - 10), &log, kMaxMessageBytes,
                      &error, &code));
  EXPECT_EQ(code, ERROR_CODE_MALFORMED);
  EXPECT_THAT(error, HasSubstr("malformed kapfix.v1.Log"));
}

TEST(DecodeTest, RejectsGarbageBytes) {
  Telemetry telemetry;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(
      Decode("this is not a protobuf message", &telemetry, kMaxMessageBytes, &error, &code));
  EXPECT_EQ(code, ERROR_CODE_MALFORMED);
  EXPECT_THAT(error, HasSubstr("do not parse"));
}

TEST(DecodeTest, RejectsAMessageOverTheSizeLimit) {
  const std::string bytes = LogBytes();
  Log log;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(Decode(bytes, &log, bytes.size() - 1, &error, &code));
  EXPECT_EQ(code, ERROR_CODE_OVERSIZED);
  EXPECT_THAT(error, HasSubstr("oversized"));
  EXPECT_THAT(error, HasSubstr(std::to_string(bytes.size()) + " bytes exceed the limit of " +
                               std::to_string(bytes.size() - 1)));
}

TEST(DecodeTest, AcceptsAMessageExactlyAtTheSizeLimit) {
  const std::string bytes = LogBytes();
  Log log;
  std::string error;
  EXPECT_TRUE(Decode(bytes, &log, bytes.size(), &error)) << error;
}

TEST(DecodeTest, RejectsAnotherProtocolVersion) {
  Telemetry sent = StampedTelemetry();
  sent.mutable_header()->set_protocol_version(kProtocolVersion + 1);
  Telemetry received;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(Decode(sent.SerializeAsString(), &received, kMaxMessageBytes, &error, &code));
  EXPECT_EQ(code, ERROR_CODE_WRONG_VERSION);
  EXPECT_THAT(error, HasSubstr("wrong protocol version"));
  EXPECT_THAT(error, HasSubstr("got 2, this side speaks 1"));
}

TEST(DecodeTest, RejectsAnUnsetProtocolVersion) {
  Telemetry sent = StampedTelemetry();
  sent.mutable_header()->set_protocol_version(0);
  Telemetry received;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(Decode(sent.SerializeAsString(), &received, kMaxMessageBytes, &error, &code));
  EXPECT_EQ(code, ERROR_CODE_WRONG_VERSION);
  EXPECT_THAT(error, HasSubstr("got 0 (unset)"));
}

TEST(DecodeTest, RejectsAMessageWithoutHeader) {
  Telemetry sent = StampedTelemetry();
  sent.clear_header();
  Telemetry received;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(Decode(sent.SerializeAsString(), &received, kMaxMessageBytes, &error, &code));
  EXPECT_EQ(code, ERROR_CODE_MISSING_HEADER);
  EXPECT_THAT(error, HasSubstr("kapfix.v1.Telemetry carries no header"));
}

TEST(DecodeTest, RejectsATypeThatDoesNotTravelAlone) {
  Rect rect;
  rect.set_width(5);
  Rect out;
  std::string error;
  ErrorCode code = ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(Decode(rect.SerializeAsString(), &out, kMaxMessageBytes, &error, &code));
  EXPECT_EQ(code, ERROR_CODE_INTERNAL);
  EXPECT_THAT(error, HasSubstr("not a link message"));
}

TEST(DecodeTest, LeavesTheOutputClearedOnFailure) {
  Telemetry sent = StampedTelemetry();
  sent.mutable_header()->set_protocol_version(kProtocolVersion + 1);
  Telemetry received = StampedTelemetry();  // stale content from an earlier message
  std::string error;
  ASSERT_FALSE(Decode(sent.SerializeAsString(), &received, kMaxMessageBytes, &error));
  EXPECT_EQ(received.ByteSizeLong(), 0U);
}

TEST(DecodeTest, KeepsFieldsAddedByANewerPeer) {
  // A compatible v1 addition (a field number this build does not know) must not be refused.
  std::string bytes = StampedTelemetry().SerializeAsString();
  bytes += std::string("\xb8\x3e\x05", 3);  // field 1000, varint, value 5
  Telemetry received;
  std::string error;
  ASSERT_TRUE(Decode(bytes, &received, kMaxMessageBytes, &error)) << error;
  EXPECT_EQ(received.frame_number(), 1234U);
  EXPECT_EQ(received.SerializeAsString(), bytes);
}

TEST(StampTest, SetsProtocolVersionAgentIdAndSequence) {
  Header header;
  Stamp(&header, "boat-2", 99);
  EXPECT_EQ(header.protocol_version(), kProtocolVersion);
  EXPECT_EQ(header.agent_id(), "boat-2");
  EXPECT_EQ(header.sequence(), 99U);
}

TEST(StampTest, SetsSendTimeToNow) {
  Header header;
  const std::int64_t before = NowMicros();
  Stamp(&header, "boat-2", 1);
  const std::int64_t after = NowMicros();
  EXPECT_GE(header.send_time_us(), before);
  EXPECT_LE(header.send_time_us(), after);
  EXPECT_GT(before, 1'600'000'000'000'000);  // µs since the epoch, not ms or s
}

TEST(StampTest, KeepsACaptureTimeAlreadySet) {
  Header header;
  header.set_capture_time_us(1'700'000'000'000'123);
  Stamp(&header, "boat-2", 1);
  EXPECT_EQ(header.capture_time_us(), 1'700'000'000'000'123);
}

TEST(StampTest, SetsAnUnsetCaptureTimeToTheSendTime) {
  Header header;
  Stamp(&header, "boat-2", 1);
  EXPECT_EQ(header.capture_time_us(), header.send_time_us());
}

}  // namespace
}  // namespace kapfix::v1
