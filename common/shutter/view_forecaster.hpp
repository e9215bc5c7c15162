#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>

namespace kapfix {

// One frame of the loop as the shutter sees it.
struct ShutterFrame {
  std::int64_t time_us = 0;  // [µs] the frame's capture time
  cv::Point2d offset_px;     // [px] measured residual displacement of the view
  bool trusted = false;      // the match was found and the lock is trusted
  double pan_deg = 0;        // [deg] servo angles the frame was seen through
  double tilt_deg = 0;
};

// What a shutter needs to know of the view's future: a seam, so the shutter's choice can be
// tested on scripted forecasts (SwingViewForecaster is the real one).
class ViewForecaster {
 public:
  virtual ~ViewForecaster() = default;
  // Every frame, in order.
  virtual void Observe(const ShutterFrame& frame) = 0;
  // A model of the view is fitted and its error measured: its forecasts mean something.
  virtual bool trained() const = 0;
  // [px] the residual offset expected `frames` (≥ 1) after the newest frame.
  virtual cv::Point2d Forecast(int frames) const = 0;
  // [px] RMS of the one-step forecast error per axis: what the model cannot foresee.
  virtual cv::Point2d error_rms() const = 0;
  // [frames] the platform's swing period, when one is seen.
  virtual std::optional<double> period_frames() const = 0;
};

}  // namespace kapfix
