// VideoDownlink: a frame becomes a scaled JPEG with the overlay the station draws; at most
// `fps` frames per second of camera time are taken, none at 0. Flush waits for the encoder
// thread, so no test waits on time.
#include "agent/downlink/video_downlink.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "tests/agent/support/recording_stream_sink.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::RecordingStreamSink;

CapturedFrame Frame(std::uint64_t index, std::int64_t time_us, cv::Size size = {64, 48}) {
  cv::Mat image(size, CV_8UC3);
  cv::RNG rng(index + 1);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return CapturedFrame{image, time_us, index};
}

FrameOutcome FixatingOutcome() {
  FrameOutcome outcome;
  outcome.mode = AgentMode::kFixate;
  outcome.slice = 4;
  outcome.slice_count = 9;
  outcome.patch = cv::Rect(110, 80, 100, 100);
  return outcome;
}

TelemetryRecord FoundAt(double x_px, double y_px) {
  TelemetryRecord record;
  record.found = true;
  record.displacement_x_px = x_px;
  record.displacement_y_px = y_px;
  return record;
}

kapfix::v1::VideoSettings Video(float fps, float scale = 0.5F) {
  kapfix::v1::VideoSettings video;
  video.set_fps(fps);
  video.set_scale(scale);
  video.set_jpeg_quality(80);
  return video;
}

// Every frame the downlink took from the control thread ends up sent or dropped.
std::uint64_t Taken(const VideoDownlink& downlink) { return downlink.sent() + downlink.dropped(); }

TEST(VideoDownlinkTest, EncodeGivesADecodableJpegOfTheScaledSize) {
  const kapfix::v1::VideoFrame message = VideoDownlink::Encode(
      Frame(5, 1000, {320, 240}), FixatingOutcome(), TelemetryRecord{}, Video(10, 0.5));
  const std::string& jpeg = message.jpeg();
  const cv::Mat decoded =
      cv::imdecode(std::vector<unsigned char>(jpeg.begin(), jpeg.end()), cv::IMREAD_COLOR);
  ASSERT_FALSE(decoded.empty());
  EXPECT_EQ(decoded.size(), cv::Size(160, 120));
  EXPECT_EQ(message.width_px(), 160u);
  EXPECT_EQ(message.height_px(), 120u);
  EXPECT_EQ(message.frame_width_px(), 320u);
  EXPECT_EQ(message.frame_height_px(), 240u);
}

TEST(VideoDownlinkTest, EncodeCarriesTheFramesNumberAndTime) {
  const kapfix::v1::VideoFrame message =
      VideoDownlink::Encode(Frame(5, 1000), FixatingOutcome(), TelemetryRecord{}, Video(10));
  EXPECT_EQ(message.frame_number(), 5u);
  EXPECT_EQ(message.header().capture_time_us(), 1000);
}

TEST(VideoDownlinkTest, OverlayShowsTheSlices) {
  const kapfix::v1::VideoFrame message =
      VideoDownlink::Encode(Frame(0, 0), FixatingOutcome(), TelemetryRecord{}, Video(10));
  EXPECT_EQ(message.overlay().slice_count(), 9u);
  EXPECT_EQ(message.overlay().chosen_slice(), 4u);
}

TEST(VideoDownlinkTest, OverlayShowsTheReferencePatch) {
  const kapfix::v1::Overlay overlay =
      VideoDownlink::Encode(Frame(0, 0), FixatingOutcome(), FoundAt(0, 0), Video(10)).overlay();
  ASSERT_TRUE(overlay.has_reference_patch());
  EXPECT_EQ(overlay.reference_patch().x(), 110);
  EXPECT_EQ(overlay.reference_patch().y(), 80);
  EXPECT_EQ(overlay.reference_patch().width(), 100);
  EXPECT_EQ(overlay.reference_patch().height(), 100);
}

TEST(VideoDownlinkTest, CurrentMatchIsThePatchShiftedByTheDisplacement) {
  const kapfix::v1::Overlay overlay =
      VideoDownlink::Encode(Frame(0, 0), FixatingOutcome(), FoundAt(5.4, -2.6), Video(10))
          .overlay();
  ASSERT_TRUE(overlay.has_match());
  EXPECT_EQ(overlay.current_match().x(), 115);
  EXPECT_EQ(overlay.current_match().y(), 77);
  EXPECT_EQ(overlay.current_match().width(), 100);
  EXPECT_EQ(overlay.current_match().height(), 100);
}

TEST(VideoDownlinkTest, NoMatchWhenThePatchWasNotFound) {
  TelemetryRecord lost = FoundAt(5, 5);
  lost.found = false;
  const kapfix::v1::Overlay overlay =
      VideoDownlink::Encode(Frame(0, 0), FixatingOutcome(), lost, Video(10)).overlay();
  EXPECT_FALSE(overlay.has_match());
  EXPECT_FALSE(overlay.has_current_match());
  EXPECT_TRUE(overlay.has_reference_patch());
}

TEST(VideoDownlinkTest, NoPatchNoMatchWithoutAReference) {
  FrameOutcome idle;
  idle.slice_count = 9;
  const kapfix::v1::Overlay overlay =
      VideoDownlink::Encode(Frame(0, 0), idle, FoundAt(1, 1), Video(10)).overlay();
  EXPECT_FALSE(overlay.has_reference_patch());
  EXPECT_FALSE(overlay.has_match());
}

TEST(VideoDownlinkTest, TakesAThirdOfA30FpsCameraAt10Fps) {
  RecordingStreamSink sink;
  VideoDownlink downlink(sink, Video(10));
  // A 30 fps camera on a microsecond clock: 33 333 µs apart, three frames 99 999 µs.
  for (std::uint64_t i = 0; i < 30; ++i) {
    downlink.OnStep(Frame(i, static_cast<std::int64_t>(i) * 33'333), FrameOutcome{},
                    TelemetryRecord{});
  }
  downlink.Flush();
  EXPECT_EQ(Taken(downlink), 10u);
  EXPECT_EQ(sink.Messages<kapfix::v1::VideoFrame>().size(), downlink.sent());
}

TEST(VideoDownlinkTest, TakesEveryThirdFrameOfA30FpsCameraAt10Fps) {
  RecordingStreamSink sink;
  VideoDownlink downlink(sink, Video(10));
  for (std::uint64_t i = 0; i < 30; ++i) {
    downlink.OnStep(Frame(i, static_cast<std::int64_t>(i) * 33'333), FrameOutcome{},
                    TelemetryRecord{});
  }
  downlink.Flush();
  EXPECT_EQ(Taken(downlink), 10u);
  const auto frames = sink.Messages<kapfix::v1::VideoFrame>();
  ASSERT_FALSE(frames.empty());
  for (const kapfix::v1::VideoFrame& frame : frames) EXPECT_EQ(frame.frame_number() % 3, 0u);
}

TEST(VideoDownlinkTest, ZeroFpsPublishesNothing) {
  RecordingStreamSink sink;
  VideoDownlink downlink(sink, Video(0));
  for (std::uint64_t i = 0; i < 30; ++i) {
    downlink.OnStep(Frame(i, static_cast<std::int64_t>(i) * 33'333), FrameOutcome{},
                    TelemetryRecord{});
  }
  downlink.Flush();
  EXPECT_EQ(sink.size(), 0u);
  EXPECT_EQ(Taken(downlink), 0u);
}

TEST(VideoDownlinkTest, SetSettingsToZeroFpsStopsTheVideo) {
  RecordingStreamSink sink;
  VideoDownlink downlink(sink, Video(10));
  downlink.SetSettings(Video(0));
  downlink.OnStep(Frame(0, 0), FrameOutcome{}, TelemetryRecord{});
  downlink.Flush();
  EXPECT_EQ(sink.size(), 0u);
  EXPECT_EQ(Taken(downlink), 0u);
}

TEST(VideoDownlinkTest, AFrameTheSinkRefusesIsCountedAsDropped) {
  RecordingStreamSink sink;
  sink.RefuseNext(1);
  VideoDownlink downlink(sink, Video(10));
  downlink.OnStep(Frame(0, 0), FrameOutcome{}, TelemetryRecord{});
  downlink.Flush();
  EXPECT_EQ(downlink.dropped(), 1u);
  EXPECT_EQ(downlink.sent(), 0u);
}

}  // namespace
}  // namespace kapfix::agent
