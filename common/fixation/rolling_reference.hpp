#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/fixation/region_roll_reader.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sample_set.hpp"

namespace kapfix {

// How the stored reference follows the camera's roll (issue 9). Pan and tilt cannot undo a
// roll; past a few degrees the translational search compares a turned view with an upright
// patch, and its minimum drifts to wherever one bright feature lines up (smarties.png at ±12°:
// the view held 8–16 px off while the match stayed confident, 26 % of the frames grossly off
// and claimed).
struct RollTrackingOptions {
  bool enabled = true;
  // How each frame's roll is read: from a region around the patch, roll and shift together.
  // A roll cannot be read from the patch alone at the displacement the upright search found:
  // where one feature dominates the patch the search answers a roll θ with a shift of r·θ, and
  // the patch read there is level (smarties.png: the view held 8–16 px off at ±12°).
  RegionRollOptions region;
  // [deg] an estimate within ± this turns nothing: below it the upright patch matches as well
  // and a world without roll flies exactly as without the tracking.
  double dead_band_deg = 1.5;
  // [deg] the reference is turned in whole steps of this (each turned copy kept for reuse); a
  // patch 100 px wide turned half a step wrong is off by ~0.4 px at its corners.
  double turn_step_deg = 1;
  // [1] the weight of each frame's read in the estimate (a blurred frame's wanders).
  double smoothing = 0.5;
  double max_deg = 30;  // [deg] the estimate is kept within ± this (the simulated world's range)
  std::size_t turned_kept = 8;  // turned references kept for reuse

  bool IsValid(std::string* error) const;
};

// The stored reference, turned by the roll the loop has read since it was taken. Every frame
// matched with confidence reads the roll (Track, RegionRollReader); the search then compares the
// next frame with the reference turned by the estimate, rounded to turn_step_deg, about the patch's
// centre, so that the patch's displacement keeps its meaning. Every turned copy is made from the
// reference as stored, so errors do not accumulate. Not thread-safe (the control thread owns it).
class RollingReference {
 public:
  // Throws std::invalid_argument for options that are not IsValid.
  explicit RollingReference(RollTrackingOptions options = {});

  // Stores `plane`'s patch `patch` with `samples` (ReferencePatch's preconditions) and
  // forgets the roll: the reference is upright by definition.
  void Reset(const cv::Mat& plane, const cv::Rect& patch, SampleSet samples);
  bool has_reference() const { return !stored_.empty(); }

  // The reference the search compares with: the stored one turned by turn_deg(). Requires
  // has_reference().
  const ReferencePatch& reference() const;
  // The reference as stored, upright.
  const ReferencePatch& stored() const { return stored_; }

  // Reads the roll of the region around the patch seen at `displacement` [px] in `plane`
  // about the estimate, and moves the estimate towards it (and the turned reference with it).
  // Nothing changes when tracking is off or the region cannot be read there. Returns the read.
  std::optional<RegionRoll> Track(const cv::Mat& plane, const cv::Point2d& displacement);

  double estimate_deg() const { return estimate_deg_; }  // [deg] smoothed reads
  double turn_deg() const { return turn_deg_; }          // [deg] what the reference is turned by

 private:
  struct Turned {
    double deg;
    std::shared_ptr<const ReferencePatch> reference;
  };
  // The reference turned by `deg` [deg], built or reused.
  std::shared_ptr<const ReferencePatch> TurnedBy(double deg);

  RollTrackingOptions options_;
  ReferencePatch stored_;
  RegionRollReader reader_;
  cv::Rect patch_;
  double estimate_deg_ = 0;
  double turn_deg_ = 0;
  std::vector<Turned> turned_;                       // most recently used last
  std::shared_ptr<const ReferencePatch> in_effect_;  // turned by turn_deg_; none: stored_
};

}  // namespace kapfix
