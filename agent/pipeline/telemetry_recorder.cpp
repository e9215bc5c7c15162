#include "agent/pipeline/telemetry_recorder.hpp"

#include <sstream>

namespace kapfix::agent {

void TelemetryRecorder::Add(const TelemetryRecord& record) {
  std::lock_guard lock(mutex_);
  records_.push_back(record);
}

std::vector<TelemetryRecord> TelemetryRecorder::records() const {
  std::lock_guard lock(mutex_);
  return records_;
}

std::size_t TelemetryRecorder::size() const {
  std::lock_guard lock(mutex_);
  return records_.size();
}

void TelemetryRecorder::OnStep(const CapturedFrame& /*frame*/, const FrameOutcome& /*outcome*/,
                               const TelemetryRecord& record) {
  Add(record);
}

std::string TelemetryRecorder::ToCsv(const std::vector<TelemetryRecord>& records) {
  std::ostringstream csv;
  csv.precision(8);
  csv << "index,capture_time_us,found,displacement_x_px,displacement_y_px,confidence,lock_lost,"
         "target_pan_deg,target_tilt_deg,angle_pan_deg,angle_tilt_deg,loop_latency_ms,"
         "mode,slice,view_offset_x_px,view_offset_y_px,pan_deg_per_px,pan_deg_per_px_sigma,"
         "tilt_deg_per_px,tilt_deg_per_px_sigma,deg_per_px_trusted,forecast_weight,off_target\n";
  for (const TelemetryRecord& r : records) {
    csv << r.index << ',' << r.capture_time_us << ',' << (r.found ? 1 : 0) << ','
        << r.displacement_x_px << ',' << r.displacement_y_px << ',' << r.confidence << ','
        << (r.lock_lost ? 1 : 0) << ',' << r.target_pan_deg << ',' << r.target_tilt_deg << ','
        << r.angle_pan_deg << ',' << r.angle_tilt_deg << ',' << r.loop_latency_ms << ','
        << ToString(r.mode) << ',' << r.slice << ',';
    if (r.view_offset_x_px) csv << *r.view_offset_x_px;
    csv << ',';
    if (r.view_offset_y_px) csv << *r.view_offset_y_px;
    // Empty cells for a controller without an online estimate.
    if (r.estimate) {
      const ControlEstimate& e = *r.estimate;
      csv << ',' << e.pan.deg_per_px << ',' << e.pan.relative_sigma << ',' << e.tilt.deg_per_px
          << ',' << e.tilt.relative_sigma << ',' << (e.pan.trusted && e.tilt.trusted ? 1 : 0) << ','
          << e.forecast_weight();
    } else {
      csv << ",,,,,";
    }
    csv << ',' << (r.off_target ? 1 : 0) << '\n';
  }
  return csv.str();
}

}  // namespace kapfix::agent
