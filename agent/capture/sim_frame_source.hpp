#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "agent/capture/camera_setting_controls.hpp"
#include "agent/capture/frame_source.hpp"
#include "common/sim/simulated_platform.hpp"

namespace kapfix::agent {

// The simulated scene camera of SPEC §3 in closed loop: a FrameSource over a SimulatedPlatform
// that SimServoDriver points. Grab waits for the next frame, as a camera does: it advances the
// platform one frame (the servos step, the swing moves on) and returns that frame; the very
// first Grab returns frame 0 without advancing. A command sent after frame t was grabbed
// therefore acts from step t → t + 1 on, exactly as in EvaluateClosedLoop.
//
// Frame times are simulated (index / fps), not wall-clock, so a flight is deterministic.
// The simulation's truth — the view's residual offset from frame 0 — is kept for the last
// frames and can be asked for by index (telemetry and the closed-loop figures use it).
class SimFrameSource : public FrameSource {
 public:
  // Throws std::invalid_argument for a null platform or fps ≤ 0. `real_time`: Grab also waits
  // for the frame's time on the wall clock, as a real camera does, so that a station sees the
  // flight at its true pace; otherwise frames come as fast as they are asked for (benchmarks,
  // tests).
  SimFrameSource(std::shared_ptr<SimulatedPlatform> platform, double fps, bool real_time = false);
  SimFrameSource(const SimFrameSource&) = delete;  // its controls point at it
  SimFrameSource& operator=(const SimFrameSource&) = delete;

  bool Open(std::string* error) override;
  bool Grab(CapturedFrame* frame, std::string* error) override;
  // The simulated camera has a gain [dB]: it scales the frame's brightness (saturating at
  // 255), the frames after it was set. Its exposure is automatic (the world's exposure steps):
  // automatic exposure on is what it does, a fixed exposure or automatic exposure off is
  // refused by name. Call from the thread that grabs.
  bool Apply(const kapfix::v1::CameraSettings& settings, std::string* error) override;
  std::string Describe() const override;

  // [px] SimulatedPlatform::ViewOffset of frame `index` while it was captured; nullopt when
  // the frame is older than the last 1024 or not captured yet. Thread-safe.
  std::optional<cv::Point2d> ViewOffset(std::uint64_t index) const;
  // Frames the simulated camera lost (SimulatedPlatformOptions::frame_drop_rate); their
  // indices are skipped, so the next frame's capture time shows the gap.
  std::uint64_t dropped() const { return dropped_; }

 private:
  bool SetGain(double db, std::string* reason);
  bool SetAutoExposure(bool on, std::string* reason);

  std::shared_ptr<SimulatedPlatform> platform_;
  double fps_;
  bool real_time_;
  std::chrono::steady_clock::time_point start_;
  bool open_ = false;
  std::uint64_t next_index_ = 0;
  std::uint64_t dropped_ = 0;
  mutable std::mutex truth_mutex_;
  std::deque<std::pair<std::uint64_t, cv::Point2d>> truth_;
  double brightness_ = 1.0;  // [1] the gain as a factor on the frame's values
  CameraSettingControls controls_;
};

}  // namespace kapfix::agent
