// A message as it travels: its topic and bytes, and the topic check on decoding.
#include "link/envelope.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"

namespace kapfix::link {
namespace {

using kapfix::v1::ErrorCode;
using kapfix::v1::kMaxMessageBytes;
using kapfix::v1::Telemetry;
using kapfix::v1::VideoFrame;
using ::testing::HasSubstr;

Telemetry StampedTelemetry() {
  Telemetry telemetry;
  kapfix::v1::Stamp(telemetry.mutable_header(), "kite-1", 3);
  telemetry.set_frame_number(1234);
  return telemetry;
}

TEST(EncodeTest, EnvelopeCarriesTopicAndSerializedMessage) {
  const Telemetry telemetry = StampedTelemetry();
  const Envelope envelope = Encode(telemetry);
  EXPECT_EQ(envelope.topic, "telemetry");
  EXPECT_EQ(envelope.payload, telemetry.SerializeAsString());
}

TEST(DecodeEnvelopeTest, AcceptsBytesUnderTheirOwnTopic) {
  const Envelope envelope = Encode(StampedTelemetry());
  Telemetry received;
  std::string error;
  EXPECT_TRUE(DecodeEnvelope(envelope.topic, envelope.payload, &received, kMaxMessageBytes, &error))
      << error;
}

TEST(DecodeEnvelopeTest, RejectsBytesUnderAnotherTopic) {
  const Envelope envelope = Encode(StampedTelemetry());
  VideoFrame received;
  std::string error;
  ErrorCode code = kapfix::v1::ERROR_CODE_UNSPECIFIED;
  EXPECT_FALSE(
      DecodeEnvelope(envelope.topic, envelope.payload, &received, kMaxMessageBytes, &error, &code));
  EXPECT_EQ(code, kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_THAT(error, HasSubstr("topic 'telemetry' does not carry kapfix.v1.VideoFrame"));
}

}  // namespace
}  // namespace kapfix::link
