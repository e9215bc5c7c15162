#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "common/control/calibration.hpp"
#include "common/control/controller.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sample_set.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix::agent {

struct CalibrationRunOptions {
  // Each axis is moved to park + m for every m of CalibrationMoves(span_deg, step_deg) [deg].
  double span_deg = 4.0;
  double step_deg = 0.8;
  // [frames] waited after each servo command before the view is read: the servos' latency
  // plus their travel.
  int settle_frames = 3;
  cv::Rect patch;  // [px] where the view is read (the slice's patch)
  SamplingOptions sampling;
  SearchOptions search;  // axis is ignored: each move is read along its own axis
  ServoTargets park;     // [deg] position each move starts from
};

// Calibration (SPEC §2.7, thesis §4.2) as a per-frame state machine for the control thread:
// for each axis and each move, the servos go to park and settle, the view at park becomes the
// reference, the servo goes to park + move and settles, and the view's displacement is read.
// The (move, displacement) pairs are fitted by CalibrateAxis when both axes are done.
class CalibrationRun {
 public:
  // The strategy must outlive the run. Throws std::invalid_argument for a bad span or step.
  CalibrationRun(CalibrationRunOptions options, const SearchStrategy& strategy);

  // One frame (a single-channel plane, see ExtractChannel); returns the servo angles to
  // command now.
  ServoTargets Step(const cv::Mat& plane);

  bool finished() const { return phase_ == Phase::kDone; }
  int moves_done() const { return moves_done_; }
  int moves_total() const { return static_cast<int>(2 * moves_.size()); }
  // Valid once finished(); throws std::invalid_argument (from CalibrateAxis) when the view
  // did not move with the servo.
  AxisCalibration FitPan() const { return CalibrateAxis(pan_samples_); }
  AxisCalibration FitTilt() const { return CalibrateAxis(tilt_samples_); }

 private:
  enum class Phase { kToPark, kToMove, kDone };
  ServoTargets Command() const;

  CalibrationRunOptions options_;
  const SearchStrategy& strategy_;
  std::vector<double> moves_;
  SampleSet samples_;
  std::optional<ReferencePatch> reference_;
  std::vector<CalibrationSample> pan_samples_;
  std::vector<CalibrationSample> tilt_samples_;
  Phase phase_ = Phase::kToPark;
  int axis_ = 0;  // 0 = pan, 1 = tilt
  std::size_t move_ = 0;
  int waited_ = 0;
  int moves_done_ = 0;
};

}  // namespace kapfix::agent
