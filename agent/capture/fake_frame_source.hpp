#pragma once

#include <google/protobuf/descriptor.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "agent/capture/frame_source.hpp"

namespace kapfix::agent {

// A FrameSource for tests: serves the given frames in a loop and fails on demand, to
// exercise the agent's handling of a lost camera without hardware. Frame times are
// synthetic (index · frame_period_us) so that tests are deterministic.
class FakeFrameSource : public FrameSource {
 public:
  // Throws std::invalid_argument when `frames` is empty or one is not BGR CV_8UC3, or when
  // the period is not positive.
  explicit FakeFrameSource(std::vector<cv::Mat> frames, std::int64_t frame_period_us = 10000);

  bool Open(std::string* error) override;
  // A copy of the next frame, as a camera hands out a fresh buffer each time.
  bool Grab(CapturedFrame* frame, std::string* error) override;
  // Keeps every setting in the schema's range (applied()), except those LackControl names,
  // which it refuses as a camera without that control does. Works before Open too.
  bool Apply(const kapfix::v1::CameraSettings& settings, std::string* error) override;
  std::string Describe() const override;

  // The next Open fails while this is set (camera unplugged).
  void FailOpen(bool fail) { fail_open_ = fail; }
  // The next `count` Grabs fail as a lost camera would; the frames after them continue where
  // the sequence stopped.
  void FailNextGrabs(int count) { fail_grabs_ = count; }

  // The camera has no control for the setting `field_number`
  // (kapfix::v1::CameraSettings::k…FieldNumber).
  void LackControl(int field_number) { lacking_.push_back(field_number); }

  // Every setting accepted since the last Open (which forgets them, as a power-cycled camera
  // does), the later value of a field replacing the earlier.
  const kapfix::v1::CameraSettings& applied() const { return applied_; }
  int apply_count() const { return apply_count_; }      // Apply calls
  int open_count() const { return open_count_; }        // successful Opens
  int open_attempts() const { return open_attempts_; }  // every Open, failed ones too

 private:
  bool Keep(const google::protobuf::FieldDescriptor& field, double value, std::string* reason);

  std::vector<cv::Mat> frames_;
  std::int64_t frame_period_us_;
  std::uint64_t next_index_ = 0;
  bool open_ = false;
  bool fail_open_ = false;
  int fail_grabs_ = 0;
  int open_count_ = 0;
  int open_attempts_ = 0;
  std::vector<int> lacking_;
  kapfix::v1::CameraSettings applied_;
  int apply_count_ = 0;
};

}  // namespace kapfix::agent
