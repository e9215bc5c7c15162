#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace kapfix {

// How far the view has turned about the optical axis since the reference, read from the
// fixated patch (issue 9's honest lock). A camera under a kite line rolls; pan and tilt cannot
// undo a roll, and a patch r px from the frame centre then moves by about roll × r while the
// centre does not: holding an off-centre slice's patch leaves the view centre that far off
// (realistic world, 3° at 160 px: 8 px), and a loop that judges "on target" by the patch alone
// claims a view it does not hold.
struct PatchRollOptions {
  double max_deg = 6;  // [deg] the roll searched: centre_deg − max_deg … centre_deg + max_deg
  double centre_deg = 0;  // [deg] the roll the search is centred on (a roll already tracked)
  double step_deg = 1;    // [deg] between the angles tried; parabolas refine the best
  // [px] left out at each side of the patch: the rotated reference's corners leave it there
  int margin_px = 8;
  // The patch and frame are reduced by this factor (area average) before the fit: 2 costs
  // ~1/8 of 1 but reads the roll ~0.4° less precisely (aero1.jpg, 1°–3°: 1.39 for 1, 2.64
  // for 3), a texture's fine detail being what pins the angle.
  int reduce = 1;

  bool IsValid(std::string* error) const;
};

// The roll that best maps the reference patch `patch` of `reference_plane` onto
// `current_plane`, found together with the patch's displacement: the angle is searched on a
// grid (SSD over the patch's inside), then angle and displacement are refined in turn by
// parabolas (a displacement 1 px off moves the angle alone by ~0.5°).
struct PatchRoll {
  // [rad] positive for content turning from +x towards +y (clockwise on the screen)
  double roll_rad = 0;
  // [px] the patch's displacement refined with it (stored-reference convention)
  cv::Point2d displacement{0, 0};
};

// `displacement` [px]: where the search saw the patch (patch + displacement). Both planes
// single- or three-channel, 8 or 16 bit, the same type. Nothing when the displaced patch's
// inside (margin_px in from its sides, with a pixel or two to refine in) leaves the frame,
// or when the refinement strays from `displacement` (the search saw the patch elsewhere).
std::optional<PatchRoll> ReadPatchRoll(const cv::Mat& reference_plane, const cv::Rect& patch,
                                       const cv::Mat& current_plane,
                                       const cv::Point2d& displacement,
                                       const PatchRollOptions& options);

// `plane` turned by `roll_deg` [deg] about `centre` [px] (PatchRoll's sign: content from +x
// towards +y), the same size and type, borders replicated: what a reference looks like through
// a camera that has rolled by that much since.
cv::Mat TurnedPlane(const cv::Mat& plane, const cv::Point2d& centre, double roll_deg);

// [px] Where the frame centre's content has moved, given where the patch's has (`displacement`)
// and the roll [rad] about the centre: a roll moves content at r from the centre by
// (−roll·r_y, roll·r_x), and the patch centre sits at `patch_offset` [px] from the frame
// centre.
cv::Point2d CentreDisplacement(const cv::Point2d& displacement, double roll_rad,
                               const cv::Point2d& patch_offset);

}  // namespace kapfix
