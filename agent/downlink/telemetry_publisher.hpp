#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>

#include "agent/pipeline/step_observer.hpp"
#include "agent/server/stream_sink.hpp"
#include "kapfix/v1/telemetry.pb.h"

namespace kapfix::agent {

// One kapfix.v1.Telemetry per control step (SPEC §5), published as it happens. Never dropped
// silently: the sink's refusals are counted here and reported in the next message.
class TelemetryPublisher : public StepObserver {
 public:
  // `video_dropped` reads the video downlink's drop counter for Telemetry.video_frames_dropped.
  TelemetryPublisher(StreamSink& sink, std::function<std::uint64_t()> video_dropped);

  void OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
              const TelemetryRecord& record) override;

  std::uint64_t dropped() const { return dropped_.load(); }

  // The message of one step (fps and drop counters as given).
  static kapfix::v1::Telemetry ToMessage(const TelemetryRecord& record, double fps,
                                         std::uint64_t video_dropped,
                                         std::uint64_t telemetry_dropped);

 private:
  StreamSink& sink_;
  std::function<std::uint64_t()> video_dropped_;
  std::atomic<std::uint64_t> dropped_{0};
  std::optional<std::int64_t> previous_time_us_;
  double fps_ = 0;  // [frames/s] exponential average over about 30 frames
};

kapfix::v1::Mode ToProto(AgentMode mode);
std::optional<AgentMode> FromProto(kapfix::v1::Mode mode);

}  // namespace kapfix::agent
