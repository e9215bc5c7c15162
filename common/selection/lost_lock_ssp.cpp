#include "common/selection/lost_lock_ssp.hpp"

#include <stdexcept>
#include <string>

namespace kapfix {

bool LostLockSspOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (after_frames < 0) {
    return fail("SSP after a lost lock: the wait must be ≥ 0 frames, got " +
                std::to_string(after_frames));
  }
  if (run_frames < 2) {
    return fail("SSP after a lost lock: the run must be ≥ 2 frames, got " +
                std::to_string(run_frames));
  }
  return selection.IsValid(error);
}

LostLockSsp::LostLockSsp(const SearchStrategy& strategy, LostLockSspOptions options)
    : strategy_(strategy), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

std::optional<SliceSelection> LostLockSsp::See(bool lock_lost,
                                               const std::function<cv::Mat()>& plane) {
  if (!lock_lost || options_.after_frames == 0) {
    lost_frames_ = 0;
    run_.reset();
    return std::nullopt;
  }
  ++lost_frames_;
  if (!run_) {
    // The stretch's first after_frames frames leave re-acquisition its chance: the view swings
    // through the reference twice a period.
    if (lost_frames_ > options_.after_frames) run_.emplace(plane(), strategy_, options_.selection);
    return std::nullopt;
  }
  run_->AddFrame(plane());
  if (run_->frames_used() < options_.run_frames) return std::nullopt;
  SliceSelection selection = run_->Result(/*deadline_hit=*/false);
  run_.reset();
  // A lock still lost waits a whole stretch again before the next run.
  lost_frames_ = 0;
  return selection;
}

}  // namespace kapfix
