#pragma once

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
  bool SetGain(double gain_db, std::string* error) override;
  bool SetExposure(double exposure_us, std::string* error) override;
  std::string Describe() const override;

  // The next Open fails while this is set (camera unplugged).
  void FailOpen(bool fail) { fail_open_ = fail; }
  // The next `count` Grabs fail as a lost camera would; the frames after them continue where
  // the sequence stopped.
  void FailNextGrabs(int count) { fail_grabs_ = count; }

  double gain_db() const { return gain_db_; }           // [dB] last accepted
  double exposure_us() const { return exposure_us_; }   // [µs] last accepted
  int open_count() const { return open_count_; }        // successful Opens
  int open_attempts() const { return open_attempts_; }  // every Open, failed ones too

 private:
  std::vector<cv::Mat> frames_;
  std::int64_t frame_period_us_;
  std::uint64_t next_index_ = 0;
  bool open_ = false;
  bool fail_open_ = false;
  int fail_grabs_ = 0;
  int open_count_ = 0;
  int open_attempts_ = 0;
  double gain_db_ = 0;
  double exposure_us_ = 0;
};

}  // namespace kapfix::agent
