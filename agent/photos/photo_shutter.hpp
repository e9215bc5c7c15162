#pragma once

#include <deque>
#include <mutex>
#include <optional>

#include "agent/pipeline/step_observer.hpp"
#include "common/shutter/best_phase_shutter.hpp"
#include "common/shutter/swing_view_forecaster.hpp"
#include "kapfix/v1/settings.pb.h"

namespace kapfix::agent {

// When the PhotoTaker's photo is taken (issue 13): the BestPhaseShutter over a
// SwingViewForecaster fed each control step's measured residual offset and servo angles.
// The frame period is measured from the frames' capture times (the median of the recent
// intervals), so a camera that runs slower than configured is planned for as it runs.
// Set() may come from any thread; the rest is the control thread's.
class PhotoShutter {
 public:
  PhotoShutter();

  // The photo settings to use from the next frame on (an open window keeps its end).
  // `settings` must have every field set (AgentConfig::IsValid).
  void Set(const kapfix::v1::PhotoSettings& settings);

  void Request();  // a photo is wanted: opens a window at the next frame
  bool window_open() const { return shutter_.window_open(); }
  // Every control step. The shot when the shutter fires on this frame.
  std::optional<ShutterShot> OnStep(const CapturedFrame& frame, const TelemetryRecord& record);

 private:
  std::mutex mutex_;
  std::optional<kapfix::v1::PhotoSettings> pending_;  // guarded by mutex_

  SwingViewForecaster forecaster_;
  BestPhaseShutter shutter_;
  std::optional<std::int64_t> last_time_us_;
  std::deque<std::int64_t> intervals_us_;  // [µs] between the last frames, newest last
};

}  // namespace kapfix::agent
