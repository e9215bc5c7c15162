#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace kapfix::agent {

// One control step, as the station's Telemetry message will carry it (issue 3).
struct TelemetryRecord {
  std::uint64_t index = 0;           // frame index from the FrameSource
  std::int64_t capture_time_us = 0;  // [µs] the frame's capture time
  bool found = false;                // the matcher found the patch
  double displacement_x_px = 0;      // [px] measured, stored-reference convention
  double displacement_y_px = 0;      // [px]
  double confidence = 0;             // [0, 1]
  bool lock_lost = false;
  double target_pan_deg = 0;  // [deg] what the controller asked for
  double target_tilt_deg = 0;
  double angle_pan_deg = 0;  // [deg] what the limited driver commanded
  double angle_tilt_deg = 0;
  double loop_latency_ms = 0;  // [ms] frame taken → servos commanded (wall clock)
  // [px] simulation only: the view's true residual offset from the reference frame's view.
  std::optional<double> view_offset_x_px;
  std::optional<double> view_offset_y_px;
};

// Keeps every record (SPEC §4: telemetry is never dropped silently) until the run ends;
// thread-safe. A flight of 30 s at 30 frames/s is 900 records of ~120 bytes.
class TelemetryRecorder {
 public:
  void Add(const TelemetryRecord& record);
  std::vector<TelemetryRecord> records() const;
  std::size_t size() const;
  // CSV with a header row; empty cells for absent view offsets.
  static std::string ToCsv(const std::vector<TelemetryRecord>& records);

 private:
  mutable std::mutex mutex_;
  std::vector<TelemetryRecord> records_;
};

}  // namespace kapfix::agent
