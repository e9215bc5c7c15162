#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace kapfix {

// How the roll is read from the frame around the patch (RegionRollReader).
struct RegionRollOptions {
  // [px] the region read reaches this far beyond the patch on each side (less towards the
  // frame's edge). A patch alone cannot always tell a roll from a shift: where one feature
  // dominates it (smarties.png: a cluster of sweets 70 px above the patch centre), a roll θ
  // looks like a shift of 70·θ, and a search of the turned patch slides along that valley. A
  // region 2–3 × wider holds features on every side.
  int grow_px = 60;
  // The planes are reduced by this (area average) before the read: a 220 px region at 1/4 is
  // 55 × 55 px.
  int reduce = 4;
  // [deg] a read farther than this from the angle it started from is refused: the alignment
  // slid to another fit.
  double max_change_deg = 10;
  // [1] a read whose enhanced correlation coefficient (cv::findTransformECC: 1 = the same
  // region, turned and shifted) is below this is refused.
  double min_correlation = 0.6;
  int iterations = 20;  // of the alignment at most

  bool IsValid(std::string* error) const;
};

// One read: the roll and shift that best map the reference region onto the frame.
struct RegionRoll {
  double roll_deg = 0;             // [deg] PatchRoll's sign: content from +x towards +y
  cv::Point2d displacement{0, 0};  // [px] of the patch centre (stored-reference convention)
  double correlation = 0;          // [1] how well the region matched, turned and shifted
};

// Reads the camera's roll since the reference from a region around the patch: the reduced
// reference region is aligned onto the reduced frame by a rotation about the patch centre and
// a shift together (cv::findTransformECC, a Euclidean motion, from the angle and displacement
// the loop already has). Roll and shift are solved together, so a roll is not taken for the
// shift a dominant feature makes of it; the correlation it maximises is blind to brightness,
// so an exposure step does not pull it. Immutable after construction.
class RegionRollReader {
 public:
  RegionRollReader() = default;
  // `reference_plane`: CV_8UC1, CV_16UC1 or CV_8UC3; `patch` inside it. Throws
  // std::invalid_argument for options that are not IsValid.
  RegionRollReader(const cv::Mat& reference_plane, const cv::Rect& patch,
                   RegionRollOptions options);

  // Starting from `start_deg` [deg] and the patch's `displacement` [px] in `plane` (of the
  // reference's size and type). Nothing without a region (no reference, or a patch as large as
  // the frame), when the alignment does not converge, or when the read is refused (above).
  std::optional<RegionRoll> Read(const cv::Mat& plane, const cv::Point2d& displacement,
                                 double start_deg) const;

 private:
  RegionRollOptions options_;
  cv::Mat region_;        // the reference region reduced, grey floats
  cv::Rect region_rect_;  // [px] where it lies in the reference frame (a multiple of reduce)
  cv::Point2d centre_;    // [px] the patch centre in the reference frame: the roll's centre
};

}  // namespace kapfix
