#include "groundstation/plots/telemetry_series.hpp"

#include <QIODevice>
#include <QTextStream>

namespace kapfix::station {

const TelemetrySample& TelemetrySeries::append(const kapfix::v1::Telemetry& telemetry) {
  const std::int64_t capture_us = telemetry.header().capture_time_us();
  if (!session_empty_ && capture_us < newest_us_) {
    ++clock_restarts_;
    startSession();
  }
  if (session_empty_) {
    origin_us_ = capture_us;
    session_empty_ = false;
  }
  newest_us_ = capture_us;
  TelemetrySample sample;
  sample.session = session_;
  sample.capture_us = capture_us;
  sample.time_s = static_cast<double>(capture_us - origin_us_) / 1e6;
  sample.frame = telemetry.frame_number();
  const auto& displacement = telemetry.displacement();
  sample.x_px = displacement.x_px() + static_cast<double>(displacement.x_subpx());
  sample.y_px = displacement.y_px() + static_cast<double>(displacement.y_subpx());
  sample.confidence = telemetry.confidence();
  sample.distance = static_cast<double>(telemetry.distance());
  sample.pan_target_deg = telemetry.pan_target_deg();
  sample.tilt_target_deg = telemetry.tilt_target_deg();
  sample.pan_deg = telemetry.pan_angle_deg();
  sample.tilt_deg = telemetry.tilt_angle_deg();
  samples_.push_back(sample);
  ++appended_;
  if (samples_.size() > capacity_) samples_.pop_front();
  return samples_.back();
}

void TelemetrySeries::startSession() {
  ++session_;
  session_empty_ = true;
}

void TelemetrySeries::clear() {
  samples_.clear();
  appended_ = 0;
  session_empty_ = true;
}

void TelemetrySeries::writeCsv(QIODevice& out) const {
  QTextStream stream(&out);
  stream << "session,time_s,frame,x_px,y_px,confidence,distance,pan_target_deg,tilt_target_deg,"
            "pan_deg,tilt_deg,capture_time_us\n";
  stream.setRealNumberPrecision(9);
  for (const TelemetrySample& s : samples_) {
    stream << s.session << ',' << s.time_s << ',' << s.frame << ',' << s.x_px << ',' << s.y_px
           << ',' << s.confidence << ',' << s.distance << ',' << s.pan_target_deg << ','
           << s.tilt_target_deg << ',' << s.pan_deg << ',' << s.tilt_deg << ',' << s.capture_us
           << '\n';
  }
}

}  // namespace kapfix::station
