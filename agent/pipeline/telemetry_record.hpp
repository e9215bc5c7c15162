#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>

#include "agent/modes/agent_mode.hpp"
#include "agent/pipeline/device_health.hpp"
#include "common/control/controller.hpp"

namespace kapfix::agent {

// One control step, as kapfix.v1.Telemetry carries it.
struct TelemetryRecord {
  std::uint64_t index = 0;           // frame index from the FrameSource
  std::int64_t capture_time_us = 0;  // [µs] the frame's capture time
  bool found = false;                // the matcher found the patch
  double displacement_x_px = 0;      // [px] measured, stored-reference convention
  double displacement_y_px = 0;      // [px]
  double confidence = 0;             // [0, 1]
  bool lock_lost = false;
  // The loop does not claim to hold the view (FixationLoop::Step::off_target; lost included).
  bool off_target = false;
  double target_pan_deg = 0;  // [deg] what the controller asked for
  double target_tilt_deg = 0;
  double angle_pan_deg = 0;  // [deg] what the limited driver commanded
  double angle_tilt_deg = 0;
  double loop_latency_ms = 0;  // [ms] frame taken → servos commanded (wall clock)
  AgentMode mode = AgentMode::kIdle;
  int slice = 0;              // [1..slice_count] slice in use; 0 = none
  std::int64_t distance = 0;  // [grey level²] SSD at the match
  // fixate: the frame whose view is held, or (a view resumed after a restart) the frame
  // that found the stored view, displaced there by reference_seen_at [px] (stored-reference
  // convention: a perfect match measures held view − this frame's view)
  std::optional<std::uint64_t> reference_frame;
  cv::Point2d reference_seen_at{0, 0};
  DeviceHealth camera_health;  // after this step's servo command
  DeviceHealth servo_health;
  // [px] simulation only: the view's true offset from frame 0's view (SimulatedPlatform).
  std::optional<double> view_offset_x_px;
  std::optional<double> view_offset_y_px;
  // The controller's online deg/px estimate and forecast weight after this step (issue 9);
  // none for a controller that does not learn in flight, or outside fixation.
  std::optional<ControlEstimate> estimate;
};

}  // namespace kapfix::agent
