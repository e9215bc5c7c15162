#include "common/fixation/rolling_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/fixation/patch_roll.hpp"

namespace kapfix {

bool RollTrackingOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!region.IsValid(error)) return false;
  if (!(max_deg > 0 && max_deg <= 45)) return fail("roll tracking range must be in (0, 45] deg");
  if (!(dead_band_deg >= 0 && dead_band_deg < max_deg)) {
    return fail("roll tracking dead band must be in [0, range) deg");
  }
  if (!(turn_step_deg > 0 && turn_step_deg <= 5)) {
    return fail("roll turn step must be in (0, 5] deg");
  }
  if (!(smoothing > 0 && smoothing <= 1)) return fail("roll smoothing must be in (0, 1]");
  if (turned_kept < 1) return fail("at least one turned reference must be kept");
  return true;
}

RollingReference::RollingReference(RollTrackingOptions options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("RollingReference: " + error);
}

void RollingReference::Reset(const cv::Mat& plane, const cv::Rect& patch, SampleSet samples) {
  stored_ = ReferencePatch(plane, std::move(samples));
  reader_ = options_.enabled ? RegionRollReader(plane, patch, options_.region) : RegionRollReader();
  patch_ = patch;
  estimate_deg_ = 0;
  turn_deg_ = 0;
  turned_.clear();
  in_effect_.reset();
}

const ReferencePatch& RollingReference::reference() const {
  return in_effect_ ? *in_effect_ : stored_;
}

std::optional<RegionRoll> RollingReference::Track(const cv::Mat& plane,
                                                  const cv::Point2d& displacement) {
  if (!options_.enabled || !has_reference()) return std::nullopt;
  const std::optional<RegionRoll> read = reader_.Read(plane, displacement, estimate_deg_);
  if (!read) return std::nullopt;
  const double read_deg = read->roll_deg;
  estimate_deg_ = std::clamp(estimate_deg_ + options_.smoothing * (read_deg - estimate_deg_),
                             -options_.max_deg, options_.max_deg);
  // The turn in effect moves only when the estimate is past the dead band and more than
  // 0.6 of a step from it, so that an estimate between two steps does not flip the reference
  // (and pyr's derived copy of it) frame after frame.
  const double step = options_.turn_step_deg;
  const double wanted = std::abs(estimate_deg_) < options_.dead_band_deg
                            ? 0.0
                            : std::round(estimate_deg_ / step) * step;
  if (wanted != turn_deg_ && std::abs(estimate_deg_ - turn_deg_) > 0.6 * step) {
    turn_deg_ = wanted;
    in_effect_ = wanted == 0.0 ? nullptr : TurnedBy(wanted);
  }
  return read;
}

std::shared_ptr<const ReferencePatch> RollingReference::TurnedBy(double deg) {
  const auto kept =
      std::find_if(turned_.begin(), turned_.end(), [deg](const Turned& t) { return t.deg == deg; });
  if (kept != turned_.end()) {
    std::rotate(kept, kept + 1, turned_.end());  // to the back: most recently used
    return turned_.back().reference;
  }
  const cv::Point2d centre(patch_.x + 0.5 * (patch_.width - 1),
                           patch_.y + 0.5 * (patch_.height - 1));
  turned_.push_back({deg, std::make_shared<const ReferencePatch>(
                              TurnedPlane(stored_.image(), centre, deg), stored_.samples())});
  if (turned_.size() > options_.turned_kept) turned_.erase(turned_.begin());
  return turned_.back().reference;
}

}  // namespace kapfix
