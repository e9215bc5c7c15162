// TelemetryPublisher: one Telemetry message per control step with every field of the record;
// messages the sink refuses are counted and reported in the next one.
#include "agent/downlink/telemetry_publisher.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "tests/agent/support/recording_stream_sink.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::RecordingStreamSink;

constexpr std::array kAllModes{AgentMode::kIdle,
                               AgentMode::kCalibrate,
                               AgentMode::kPss,
                               AgentMode::kSsp,
                               AgentMode::kFixate,
                               AgentMode::kFollow,
                               AgentMode::kRecordFreeSwing};

TEST(TelemetryPublisherTest, EveryMessageCarriesTheDevicesHealth) {
  TelemetryRecord record;
  record.servo_health = DeviceHealth::Lost("maestro /dev/ttyACM0: write: Input/output error");
  const kapfix::v1::Telemetry t = TelemetryPublisher::ToMessage(record, 0, 0, 0);
  EXPECT_EQ(t.camera_health().status(), kapfix::v1::DEVICE_OK);
  EXPECT_EQ(t.servo_health().status(), kapfix::v1::DEVICE_LOST);
  EXPECT_EQ(t.servo_health().reason(), "maestro /dev/ttyACM0: write: Input/output error");
  std::string bytes;
  EXPECT_TRUE(t.SerializeToString(&bytes));
}

TEST(TelemetryPublisherTest, TheOnlineDegPerPxEstimateAndForecastWeightAreCarried) {
  TelemetryRecord record;
  ControlEstimate e;
  e.pan = {0.105, 0.03, true, 0.8};
  e.tilt = {0.095, 0.05, true, 0.6};
  record.estimate = e;
  const kapfix::v1::Telemetry t = TelemetryPublisher::ToMessage(record, 0, 0, 0);
  ASSERT_TRUE(t.has_deg_per_px());
  EXPECT_FLOAT_EQ(t.deg_per_px().pan_deg_per_px(), 0.105f);
  EXPECT_FLOAT_EQ(t.deg_per_px().tilt_deg_per_px(), 0.095f);
  EXPECT_FLOAT_EQ(t.deg_per_px().pan_uncertainty(), 0.03f);
  EXPECT_FLOAT_EQ(t.deg_per_px().tilt_uncertainty(), 0.05f);
  EXPECT_TRUE(t.deg_per_px().trusted());
  EXPECT_FLOAT_EQ(t.forecast_weight(), 0.7f);
}

TEST(TelemetryPublisherTest, AnEstimateTrustedOnOneAxisOnlyIsNotTrusted) {
  TelemetryRecord record;
  ControlEstimate e;
  e.pan.trusted = true;
  record.estimate = e;
  EXPECT_FALSE(TelemetryPublisher::ToMessage(record, 0, 0, 0).deg_per_px().trusted());
}

TEST(TelemetryPublisherTest, AControllerWithoutAnEstimateSendsNone) {
  const kapfix::v1::Telemetry t = TelemetryPublisher::ToMessage(TelemetryRecord{}, 0, 0, 0);
  EXPECT_FALSE(t.has_deg_per_px());
  EXPECT_FLOAT_EQ(t.forecast_weight(), 0.0f);
}

TEST(TelemetryPublisherTest, DisplacementIsSplitIntoWholeAndSubPixelParts) {
  TelemetryRecord record;
  record.displacement_x_px = 3.25;
  record.displacement_y_px = -2.625;
  const kapfix::v1::Telemetry t = TelemetryPublisher::ToMessage(record, 0, 0, 0);
  EXPECT_EQ(t.displacement().x_px(), 3);
  EXPECT_FLOAT_EQ(t.displacement().x_subpx(), 0.25F);
  EXPECT_EQ(t.displacement().y_px(), -3);
  EXPECT_FLOAT_EQ(t.displacement().y_subpx(), 0.375F);
}

TEST(TelemetryPublisherTest, SubPixelPartStaysWithinHalfAPixel) {
  for (double px = -3.0; px <= 3.0; px += 0.125) {
    TelemetryRecord record;
    record.displacement_x_px = px;
    const kapfix::v1::Telemetry t = TelemetryPublisher::ToMessage(record, 0, 0, 0);
    EXPECT_LE(std::abs(t.displacement().x_subpx()), 0.5F) << px;
    EXPECT_NEAR(static_cast<double>(t.displacement().x_px()) + t.displacement().x_subpx(), px, 1e-6)
        << px;
  }
}

TEST(TelemetryPublisherTest, EveryModeSurvivesTheRoundTripThroughTheProto) {
  for (const AgentMode mode : kAllModes) {
    const kapfix::v1::Mode proto = ToProto(mode);
    EXPECT_NE(proto, kapfix::v1::MODE_UNSPECIFIED) << ToString(mode);
    EXPECT_EQ(FromProto(proto), mode) << ToString(mode);
  }
}

TEST(TelemetryPublisherTest, ModesMapToDistinctProtoValues) {
  for (std::size_t a = 0; a < kAllModes.size(); ++a) {
    for (std::size_t b = a + 1; b < kAllModes.size(); ++b) {
      EXPECT_NE(ToProto(kAllModes[a]), ToProto(kAllModes[b]));
    }
  }
}

TEST(TelemetryPublisherTest, UnspecifiedProtoModeIsNoMode) {
  EXPECT_EQ(FromProto(kapfix::v1::MODE_UNSPECIFIED), std::nullopt);
  EXPECT_EQ(FromProto(static_cast<kapfix::v1::Mode>(99)), std::nullopt);
}

TEST(TelemetryPublisherTest, LoopLatencyIsInMicroseconds) {
  TelemetryRecord record;
  record.loop_latency_ms = 2.5;
  EXPECT_EQ(TelemetryPublisher::ToMessage(record, 0, 0, 0).loop_latency_us(), 2500u);
}

TEST(TelemetryPublisherTest, MessageCarriesTheRecordsFields) {
  TelemetryRecord record;
  record.index = 42;
  record.capture_time_us = 123456;
  record.mode = AgentMode::kFixate;
  record.slice = 7;
  record.confidence = 0.5;
  record.distance = 999;
  record.lock_lost = true;
  record.target_pan_deg = 1.5;
  record.target_tilt_deg = -0.5;
  record.angle_pan_deg = 1.25;
  record.angle_tilt_deg = -0.25;
  const kapfix::v1::Telemetry t = TelemetryPublisher::ToMessage(record, 29.5, 3, 4);
  EXPECT_EQ(t.frame_number(), 42u);
  EXPECT_EQ(t.header().capture_time_us(), 123456);
  EXPECT_EQ(t.mode(), kapfix::v1::MODE_FIXATE);
  EXPECT_EQ(t.slice(), 7u);
  EXPECT_FLOAT_EQ(t.confidence(), 0.5F);
  EXPECT_EQ(t.distance(), 999);
  EXPECT_TRUE(t.lock_lost());
  EXPECT_FLOAT_EQ(t.pan_target_deg(), 1.5F);
  EXPECT_FLOAT_EQ(t.tilt_target_deg(), -0.5F);
  EXPECT_FLOAT_EQ(t.pan_angle_deg(), 1.25F);
  EXPECT_FLOAT_EQ(t.tilt_angle_deg(), -0.25F);
  EXPECT_FLOAT_EQ(t.fps(), 29.5F);
  EXPECT_EQ(t.video_frames_dropped(), 3u);
  EXPECT_EQ(t.telemetry_dropped(), 4u);
}

TEST(TelemetryPublisherTest, OnStepPublishesOneMessagePerStep) {
  RecordingStreamSink sink;
  TelemetryPublisher publisher(sink, nullptr);
  for (std::uint64_t i = 0; i < 3; ++i) {
    TelemetryRecord record;
    record.index = i;
    publisher.OnStep(CapturedFrame{}, FrameOutcome{}, record);
  }
  const auto messages = sink.Messages<kapfix::v1::Telemetry>();
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[2].frame_number(), 2u);
}

TEST(TelemetryPublisherTest, RefusedMessagesAreCountedAndReportedInTheNextOne) {
  RecordingStreamSink sink;
  TelemetryPublisher publisher(sink, nullptr);
  sink.RefuseNext(2);
  TelemetryRecord record;
  for (int i = 0; i < 3; ++i) publisher.OnStep(CapturedFrame{}, FrameOutcome{}, record);
  EXPECT_EQ(publisher.dropped(), 2u);
  const auto messages = sink.Messages<kapfix::v1::Telemetry>();
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].telemetry_dropped(), 2u);
}

TEST(TelemetryPublisherTest, VideoDropCounterIsReadAtEachStep) {
  RecordingStreamSink sink;
  TelemetryPublisher publisher(sink, [] { return std::uint64_t{17}; });
  publisher.OnStep(CapturedFrame{}, FrameOutcome{}, TelemetryRecord{});
  ASSERT_EQ(sink.Messages<kapfix::v1::Telemetry>().size(), 1u);
  EXPECT_EQ(sink.Messages<kapfix::v1::Telemetry>()[0].video_frames_dropped(), 17u);
}

TEST(TelemetryPublisherTest, FpsFollowsTheCaptureTimes) {
  RecordingStreamSink sink;
  TelemetryPublisher publisher(sink, nullptr);
  for (int i = 0; i < 10; ++i) {
    TelemetryRecord record;
    record.capture_time_us = std::int64_t{i} * 40'000;  // 25 frames/s
    publisher.OnStep(CapturedFrame{}, FrameOutcome{}, record);
  }
  const auto messages = sink.Messages<kapfix::v1::Telemetry>();
  ASSERT_EQ(messages.size(), 10u);
  EXPECT_NEAR(messages.back().fps(), 25.0, 0.01);
}

}  // namespace
}  // namespace kapfix::agent
