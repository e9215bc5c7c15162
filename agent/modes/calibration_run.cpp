#include "agent/modes/calibration_run.hpp"

namespace kapfix::agent {

CalibrationRun::CalibrationRun(CalibrationRunOptions options, const SearchStrategy& strategy)
    : options_(options),
      strategy_(strategy),
      moves_(CalibrationMoves(options_.span_deg, options_.step_deg)),
      samples_({options_.patch}, options_.sampling) {}

ServoTargets CalibrationRun::Command() const {
  ServoTargets target = options_.park;
  if (phase_ != Phase::kToMove) return target;
  (axis_ == 0 ? target.pan_deg : target.tilt_deg) += moves_[move_];
  return target;
}

ServoTargets CalibrationRun::Step(const cv::Mat& plane) {
  if (phase_ == Phase::kDone) return options_.park;
  if (++waited_ <= options_.settle_frames) return Command();
  waited_ = 0;
  if (phase_ == Phase::kToPark) {
    reference_.emplace(plane, samples_);
    phase_ = Phase::kToMove;
    return Command();
  }
  // Settled at park + move: read how far the view went, along the moved axis only. A
  // separable search over both axes looks along x first, at the unmoved y: after a tilt move
  // of tens of pixels that x search lands anywhere on fine texture, and the y search with it.
  SearchOptions search = options_.search;
  search.axis = axis_ == 0 ? SearchAxis::kX : SearchAxis::kY;
  const SearchResult found = strategy_.Search(*reference_, plane, search);
  if (found.found) {
    const double moved_px = axis_ == 0 ? found.displacement.x : found.displacement.y;
    (axis_ == 0 ? pan_samples_ : tilt_samples_).push_back({moves_[move_], moved_px});
  }
  ++moves_done_;
  phase_ = Phase::kToPark;
  if (++move_ == moves_.size()) {
    move_ = 0;
    if (++axis_ == 2) phase_ = Phase::kDone;
  }
  return Command();
}

}  // namespace kapfix::agent
