#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <thread>

#include "agent/pipeline/step_observer.hpp"
#include "agent/server/stream_sink.hpp"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/video.pb.h"

namespace kapfix::agent {

// The live video to the station (SPEC §4): at most `fps` frames per second of camera time are
// taken from the control thread (a copy, nothing more) and JPEG-encoded on this downlink's
// own thread, with the overlay the station draws. A frame still waiting when a newer one is
// due is dropped and counted: the video is always the latest view, never a backlog.
class VideoDownlink : public StepObserver {
 public:
  VideoDownlink(StreamSink& sink, kapfix::v1::VideoSettings settings);
  ~VideoDownlink() override;  // joins the encoder thread
  VideoDownlink(const VideoDownlink&) = delete;
  VideoDownlink& operator=(const VideoDownlink&) = delete;

  void OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
              const TelemetryRecord& record) override;

  // Any thread; every field set and in the schema's range (AgentConfig::IsValid).
  void SetSettings(const kapfix::v1::VideoSettings& settings);
  // Any thread: waits until every frame taken so far is sent or dropped (none in the encoder).
  void Flush();
  std::uint64_t dropped() const { return dropped_.load(); }
  std::uint64_t sent() const { return sent_.load(); }

  // One camera frame as a VideoFrame message (scaled, JPEG at its quality).
  static kapfix::v1::VideoFrame Encode(const CapturedFrame& frame, const FrameOutcome& outcome,
                                       const TelemetryRecord& record,
                                       const kapfix::v1::VideoSettings& settings);

 private:
  struct Pending {
    CapturedFrame frame;
    FrameOutcome outcome;
    TelemetryRecord record;
  };
  void EncoderThread();

  StreamSink& sink_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable drained_;  // no pending frame and the encoder idle
  bool encoding_ = false;            // the encoder holds a frame
  kapfix::v1::VideoSettings settings_;
  std::optional<Pending> pending_;
  bool stop_ = false;
  std::optional<std::int64_t> last_taken_us_;  // control thread only
  std::optional<std::int64_t> previous_us_;    // control thread only: the last frame seen
  std::atomic<std::uint64_t> dropped_{0};
  std::atomic<std::uint64_t> sent_{0};
  std::thread thread_;
};

}  // namespace kapfix::agent
