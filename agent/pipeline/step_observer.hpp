#pragma once

#include "agent/capture/frame_source.hpp"
#include "agent/modes/frame_processor.hpp"
#include "agent/pipeline/telemetry_record.hpp"

namespace kapfix::agent {

// Sees every control step after the servos were commanded: the telemetry publisher, the video
// downlink, the photo trigger, the flight recorder. Runs on the control thread, which must
// never wait (SPEC §4): an observer copies what it needs and hands it to its own thread.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
                      const TelemetryRecord& record) = 0;
};

}  // namespace kapfix::agent
