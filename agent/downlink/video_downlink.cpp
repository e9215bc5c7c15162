#include "agent/downlink/video_downlink.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

namespace kapfix::agent {
namespace {

void SetRect(const cv::Rect& r, kapfix::v1::Rect* out) {
  out->set_x(r.x);
  out->set_y(r.y);
  out->set_width(r.width);
  out->set_height(r.height);
}

}  // namespace

VideoDownlink::VideoDownlink(StreamSink& sink, kapfix::v1::VideoSettings settings)
    : sink_(sink), settings_(std::move(settings)), thread_([this] { EncoderThread(); }) {}

VideoDownlink::~VideoDownlink() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void VideoDownlink::SetSettings(const kapfix::v1::VideoSettings& settings) {
  std::lock_guard lock(mutex_);
  settings_ = settings;
}

void VideoDownlink::Flush() {
  std::unique_lock lock(mutex_);
  drained_.wait(lock, [this] { return !pending_ && !encoding_; });
}

void VideoDownlink::OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
                           const TelemetryRecord& record) {
  double fps = 0;
  {
    std::lock_guard lock(mutex_);
    fps = settings_.fps();
  }
  if (fps <= 0) return;
  const auto period_us = static_cast<std::int64_t>(std::llround(1e6 / fps));
  // A frame is due when the period has passed, give or take half a camera frame: at 30 fps on
  // a microsecond clock three frames are 99 999 µs, and waiting for a fourth would send 7.5
  // instead of 10 frames per second.
  const std::int64_t slack_us = previous_us_ && frame.capture_time_us > *previous_us_
                                    ? (frame.capture_time_us - *previous_us_) / 2
                                    : 0;
  previous_us_ = frame.capture_time_us;
  if (last_taken_us_ && frame.capture_time_us - *last_taken_us_ < period_us - slack_us &&
      frame.capture_time_us >= *last_taken_us_) {
    return;
  }
  last_taken_us_ = frame.capture_time_us;
  Pending pending{CapturedFrame{frame.image.clone(), frame.capture_time_us, frame.index}, outcome,
                  record};
  {
    std::lock_guard lock(mutex_);
    if (pending_) ++dropped_;
    pending_ = std::move(pending);
  }
  wake_.notify_one();
}

kapfix::v1::VideoFrame VideoDownlink::Encode(const CapturedFrame& frame,
                                             const FrameOutcome& outcome,
                                             const TelemetryRecord& record,
                                             const kapfix::v1::VideoSettings& settings) {
  cv::Mat scaled = frame.image;
  if (settings.scale() < 1.0F) {
    cv::resize(frame.image, scaled, cv::Size(), settings.scale(), settings.scale(), cv::INTER_AREA);
  }
  std::vector<unsigned char> jpeg;
  cv::imencode(".jpg", scaled, jpeg,
               {cv::IMWRITE_JPEG_QUALITY, static_cast<int>(settings.jpeg_quality())});
  kapfix::v1::VideoFrame message;
  message.mutable_header()->set_capture_time_us(frame.capture_time_us);
  message.set_frame_number(frame.index);
  message.set_jpeg(jpeg.data(), jpeg.size());
  message.set_width_px(static_cast<std::uint32_t>(scaled.cols));
  message.set_height_px(static_cast<std::uint32_t>(scaled.rows));
  message.set_frame_width_px(static_cast<std::uint32_t>(frame.image.cols));
  message.set_frame_height_px(static_cast<std::uint32_t>(frame.image.rows));
  kapfix::v1::Overlay* overlay = message.mutable_overlay();
  overlay->set_slice_count(static_cast<std::uint32_t>(outcome.slice_count));
  overlay->set_chosen_slice(static_cast<std::uint32_t>(outcome.slice));
  if (!outcome.patch.empty()) {
    SetRect(outcome.patch, overlay->mutable_reference_patch());
    if (record.found) {
      // The displacement is current match minus reference (SPEC §1).
      const cv::Rect match(
          outcome.patch.x + static_cast<int>(std::lround(record.displacement_x_px)),
          outcome.patch.y + static_cast<int>(std::lround(record.displacement_y_px)),
          outcome.patch.width, outcome.patch.height);
      SetRect(match, overlay->mutable_current_match());
      overlay->set_has_match(true);
    }
  }
  return message;
}

void VideoDownlink::EncoderThread() {
  std::unique_lock lock(mutex_);
  while (true) {
    encoding_ = false;
    drained_.notify_all();
    wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
    if (stop_) return;
    Pending pending = std::move(*pending_);
    pending_.reset();
    encoding_ = true;
    const kapfix::v1::VideoSettings settings = settings_;
    lock.unlock();
    try {
      if (sink_.Publish(Encode(pending.frame, pending.outcome, pending.record, settings))) {
        ++sent_;
      } else {
        ++dropped_;
      }
    } catch (const cv::Exception& e) {
      ++dropped_;
      spdlog::warn("video frame {} not encoded: {}", pending.frame.index, e.what());
    }
    lock.lock();
  }
}

}  // namespace kapfix::agent
