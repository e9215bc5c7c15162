#include "agent/photos/photo_shutter.hpp"

#include <algorithm>
#include <vector>

#include "agent/config/options_from_settings.hpp"

namespace kapfix::agent {
namespace {

constexpr std::size_t kIntervals = 15;  // frame intervals the period is the median of
constexpr double kDefaultFramePeriodS = 1.0 / 30;

}  // namespace

PhotoShutter::PhotoShutter() : shutter_(forecaster_) {}

void PhotoShutter::Set(const kapfix::v1::PhotoSettings& settings) {
  std::lock_guard lock(mutex_);
  pending_ = settings;
}

void PhotoShutter::Request() { shutter_.Request(); }

std::optional<ShutterShot> PhotoShutter::OnStep(const CapturedFrame& frame,
                                                const TelemetryRecord& record) {
  if (last_time_us_ && frame.capture_time_us > *last_time_us_) {
    intervals_us_.push_back(frame.capture_time_us - *last_time_us_);
    if (intervals_us_.size() > kIntervals) intervals_us_.pop_front();
  }
  last_time_us_ = frame.capture_time_us;
  // The operator's settings as last set (the shutter's defaults are their initial values).
  BestPhaseShutterOptions options = shutter_.options();
  {
    std::lock_guard lock(mutex_);
    if (pending_) {
      options = OptionsFromSettings(*pending_, options);
      pending_.reset();
    }
  }
  options.frame_period_s = kDefaultFramePeriodS;
  if (!intervals_us_.empty()) {
    std::vector<std::int64_t> sorted(intervals_us_.begin(), intervals_us_.end());
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    options.frame_period_s = static_cast<double>(sorted[sorted.size() / 2]) / 1e6;
  }
  shutter_.SetOptions(options);

  ShutterFrame shutter_frame;
  shutter_frame.time_us = frame.capture_time_us;
  shutter_frame.offset_px = {record.displacement_x_px, record.displacement_y_px};
  shutter_frame.trusted = record.found && !record.lock_lost;
  shutter_frame.pan_deg = record.angle_pan_deg;
  shutter_frame.tilt_deg = record.angle_tilt_deg;
  return shutter_.OnFrame(shutter_frame);
}

}  // namespace kapfix::agent
