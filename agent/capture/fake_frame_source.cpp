#include "agent/capture/fake_frame_source.hpp"

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <stdexcept>

#include "agent/capture/camera_setting_controls.hpp"
#include "kapfix/v1/settings_schema.hpp"

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
  applied_.Clear();  // a camera that was away (power-cycled) has forgotten its settings
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

bool FakeFrameSource::Apply(const kapfix::v1::CameraSettings& settings, std::string* error) {
  ++apply_count_;
  // A control for every field of the message, except those the test took away.
  CameraSettingControls controls;
  const google::protobuf::Descriptor& message = *kapfix::v1::CameraSettings::descriptor();
  for (int i = 0; i < message.field_count(); ++i) {
    const google::protobuf::FieldDescriptor* field = message.field(i);
    if (std::find(lacking_.begin(), lacking_.end(), field->number()) != lacking_.end()) continue;
    controls.Add(field->number(), [this, field](double value, std::string* reason) {
      return Keep(*field, value, reason);
    });
  }
  return controls.Apply(settings, "fake camera", error);
}

bool FakeFrameSource::Keep(const google::protobuf::FieldDescriptor& field, double value,
                           std::string* reason) {
  // The fake camera's range is the schema's.
  const std::string out_of_range =
      kapfix::v1::CheckSetting(*applied_.GetDescriptor(), field.name(), value, field.name());
  if (!out_of_range.empty()) {
    if (reason) *reason = out_of_range;
    return false;
  }
  const google::protobuf::Reflection& reflection = *applied_.GetReflection();
  switch (field.cpp_type()) {
    case google::protobuf::FieldDescriptor::CPPTYPE_FLOAT:
      reflection.SetFloat(&applied_, &field, static_cast<float>(value));
      return true;
    case google::protobuf::FieldDescriptor::CPPTYPE_DOUBLE:
      reflection.SetDouble(&applied_, &field, value);
      return true;
    case google::protobuf::FieldDescriptor::CPPTYPE_BOOL:
      reflection.SetBool(&applied_, &field, value != 0);
      return true;
    default:
      if (reason) *reason = "the fake camera keeps only float and bool settings";
      return false;
  }
}

std::string FakeFrameSource::Describe() const {
  return "fake camera (" + std::to_string(frames_.size()) + " frames " +
         std::to_string(frames_.front().cols) + "x" + std::to_string(frames_.front().rows) + ")";
}

}  // namespace kapfix::agent
