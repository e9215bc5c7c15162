#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"
#include "agent/modes/swing_window.hpp"
#include "common/sampling/sample_set.hpp"

namespace kapfix::agent {

// Free-swing recording: the servos hold while the view's displacement in the slice's patch is
// measured frame to frame; at the deadline the displacement graph goes as CSV to the worker,
// which writes it into the recordings folder (ModeEvents::OnFreeSwingRecorded names it once
// written, or says why not); the mode is idle at once.
class FreeSwingRecordingMode : public Mode {
 public:
  FreeSwingRecordingMode(ModeContext& context, SwingWindow window)
      : context_(context), window_(window) {}

  AgentMode kind() const override { return AgentMode::kRecordFreeSwing; }
  // Throws std::runtime_error when no recordings folder is configured.
  void Enter(const CapturedFrame& frame, const ServoTargets& current) override;
  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;

 private:
  void Write(std::int64_t capture_time_us);

  ModeContext& context_;
  SwingWindow window_;
  ServoTargets hold_;                                     // [deg]
  std::vector<std::pair<std::int64_t, double>> samples_;  // [µs, px]
  cv::Mat previous_plane_;
  std::optional<SampleSet> sample_set_;
};

}  // namespace kapfix::agent
