#include "agent/capture/fake_frame_source.hpp"

#include <cmath>
#include <stdexcept>

namespace kapfix::agent {

FakeFrameSource::FakeFrameSource(std::vector<cv::Mat> frames, std::int64_t frame_period_us)
    : frames_(std::move(frames)), frame_period_us_(frame_period_us) {
  if (frames_.empty()) throw std::invalid_argument("FakeFrameSource: no frames");
  for (const cv::Mat& f : frames_) {
    if (f.empty() || f.type() != CV_8UC3) {
      throw std::invalid_argument("FakeFrameSource: every frame must be BGR CV_8UC3");
    }
  }
  if (frame_period_us_ <= 0) throw std::invalid_argument("FakeFrameSource: period must be > 0");
}

bool FakeFrameSource::Open(std::string* error) {
  ++open_attempts_;
  if (fail_open_) {
    if (error) *error = "fake camera: not found (as told)";
    return false;
  }
  open_ = true;
  next_index_ = 0;
  ++open_count_;
  return true;
}

bool FakeFrameSource::Grab(CapturedFrame* frame, std::string* error) {
  if (!open_) {
    if (error) *error = "fake camera: not open";
    return false;
  }
  if (fail_grabs_ > 0) {
    --fail_grabs_;
    if (error) *error = "fake camera: lost (as told)";
    return false;
  }
  frame->image = frames_[next_index_ % frames_.size()].clone();
  frame->index = next_index_;
  frame->capture_time_us = static_cast<std::int64_t>(next_index_) * frame_period_us_;
  ++next_index_;
  return true;
}

bool FakeFrameSource::SetGain(double gain_db, std::string* error) {
  if (!std::isfinite(gain_db)) {
    if (error) *error = "fake camera: gain is not finite";
    return false;
  }
  gain_db_ = gain_db;
  return true;
}

bool FakeFrameSource::SetExposure(double exposure_us, std::string* error) {
  if (!std::isfinite(exposure_us) || exposure_us <= 0) {
    if (error) *error = "fake camera: exposure must be > 0 µs";
    return false;
  }
  exposure_us_ = exposure_us;
  return true;
}

std::string FakeFrameSource::Describe() const {
  return "fake camera (" + std::to_string(frames_.size()) + " frames " +
         std::to_string(frames_.front().cols) + "x" + std::to_string(frames_.front().rows) + ")";
}

}  // namespace kapfix::agent
