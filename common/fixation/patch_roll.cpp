#include "common/fixation/patch_roll.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "common/image/reduced_grey.hpp"

namespace kapfix {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// [px] how far the refinement may move the displacement in all
constexpr double kRefineReachPx = 2;

// The parabola's vertex through three equally spaced costs, in steps from the middle one
// (−0.5…0.5 when the middle is the least); 0 when they do not bend upwards.
double Vertex(double before, double at, double after) {
  const double curvature = before - 2 * at + after;
  return curvature > 0 ? 0.5 * (before - after) / curvature : 0.0;
}

// The reference patch and the current frame around where it is seen, reduced to floats at
// 1/reduce of the size, and the SSD between the patch turned by an angle and the frame at a
// displacement [full-size px].
class RollFit {
 public:
  RollFit(const cv::Mat& reference, const cv::Mat& around, cv::Point around_origin,
          cv::Point2d patch_centre, int reduce, int margin)
      : reference_(ReducedGrey(reference, reduce)),
        around_(ReducedGrey(around, reduce)),
        around_origin_(around_origin),
        patch_centre_(patch_centre),
        reduce_(reduce) {
    const int m = (margin + reduce - 1) / reduce;
    inside_ = cv::Rect(m, m, reference_.cols - 2 * m, reference_.rows - 2 * m);
  }

  bool usable() const { return inside_.width >= 4 && inside_.height >= 4; }

  cv::Mat Turned(double deg) const {
    return TurnedPlane(reference_,
                       cv::Point2d(0.5 * (reference_.cols - 1), 0.5 * (reference_.rows - 1)), deg);
  }

  cv::Mat Seen(const cv::Point2d& displacement) const {
    // A reduced pixel i covers full-size pixels reduce·i … reduce·i + reduce − 1 (INTER_AREA).
    const double half = 0.5 * (reduce_ - 1);
    const cv::Point2d full = patch_centre_ + displacement - cv::Point2d(around_origin_);
    cv::Mat seen;
    cv::getRectSubPix(around_, reference_.size(),
                      cv::Point2f(static_cast<float>((full.x - half) / reduce_),
                                  static_cast<float>((full.y - half) / reduce_)),
                      seen, CV_32F);
    return seen;
  }

  double Cost(const cv::Mat& turned, const cv::Mat& seen) const {
    return cv::norm(turned(inside_), seen(inside_), cv::NORM_L2SQR);
  }

 private:
  cv::Mat reference_;
  cv::Mat around_;
  cv::Point around_origin_;
  cv::Point2d patch_centre_;
  int reduce_;
  cv::Rect inside_;
};

// [deg] The best angle of `first + k·step` for k in [0, count), refined by a parabola.
double BestAngle(const RollFit& fit, const cv::Mat& seen, double first, double step, int count) {
  std::vector<double> cost;
  for (int k = 0; k < count; ++k) cost.push_back(fit.Cost(fit.Turned(first + k * step), seen));
  std::size_t best = 0;
  for (std::size_t k = 1; k < cost.size(); ++k) {
    if (cost[k] < cost[best]) best = k;
  }
  double offset = 0;
  if (best > 0 && best + 1 < cost.size()) {
    offset = Vertex(cost[best - 1], cost[best], cost[best + 1]);
  }
  return first + (static_cast<double>(best) + offset) * step;
}

}  // namespace

bool PatchRollOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!(max_deg > 0 && max_deg <= 45)) return fail("roll range must be in (0, 45] deg");
  if (!(std::abs(centre_deg) <= 45)) return fail("roll centre must be in [-45, 45] deg");
  if (!(step_deg > 0 && step_deg <= max_deg)) return fail("roll step must be in (0, max] deg");
  if (margin_px < 0) return fail("roll margin must be ≥ 0 px");
  if (reduce < 1 || reduce > 8) return fail("roll reduction must be 1…8");
  return true;
}

std::optional<PatchRoll> ReadPatchRoll(const cv::Mat& reference_plane, const cv::Rect& patch,
                                       const cv::Mat& current_plane,
                                       const cv::Point2d& displacement,
                                       const PatchRollOptions& options) {
  if ((patch & cv::Rect(0, 0, reference_plane.cols, reference_plane.rows)) != patch) {
    return std::nullopt;
  }
  // The frame around the displaced patch, with room for the refinement and interpolation, a
  // whole number of reduced pixels wide.
  const int k = options.reduce;
  const int room = k * (static_cast<int>(std::ceil(kRefineReachPx / k)) + 2);
  const cv::Rect around(static_cast<int>(std::floor(patch.x + displacement.x)) - room,
                        static_cast<int>(std::floor(patch.y + displacement.y)) - room,
                        patch.width + 2 * room + k, patch.height + 2 * room + k);
  // Only the patch's inside (margin_px in from each side) is compared, so the frame need hold
  // just that with the room; the rest of `around` may lie beyond the frame's edge and is
  // filled by replication (a patch on a slice clamped to the bottom edge, as SSP may choose).
  const int inset = std::min(options.margin_px, patch.width / 2 - 2);
  const cv::Rect used(around.x + inset, around.y + inset, around.width - 2 * inset,
                      around.height - 2 * inset);
  const cv::Rect frame(0, 0, current_plane.cols, current_plane.rows);
  if (inset < 0 || (used & frame) != used) return std::nullopt;
  cv::Mat around_plane;
  if ((around & frame) == around) {
    around_plane = current_plane(around);
  } else {
    const cv::Rect inside = around & frame;
    cv::copyMakeBorder(current_plane(inside), around_plane, inside.y - around.y,
                       around.br().y - inside.br().y, inside.x - around.x,
                       around.br().x - inside.br().x, cv::BORDER_REPLICATE);
  }
  // A patch a whole number of reduced pixels wide, centred where the patch is.
  const cv::Rect fitted(patch.x + (patch.width % k) / 2, patch.y + (patch.height % k) / 2,
                        patch.width - patch.width % k, patch.height - patch.height % k);
  const RollFit fit(
      reference_plane(fitted), around_plane, around.tl(),
      cv::Point2d(fitted.x + 0.5 * (fitted.width - 1), fitted.y + 0.5 * (fitted.height - 1)), k,
      options.margin_px);
  if (!fit.usable()) return std::nullopt;

  const int steps = static_cast<int>(std::floor(options.max_deg / options.step_deg));
  PatchRoll read{0, displacement};
  double deg = BestAngle(fit, fit.Seen(displacement), options.centre_deg - steps * options.step_deg,
                         options.step_deg, 2 * steps + 1);
  constexpr int kPasses = 3;  // angle and displacement in turn; each pass halves the step
  double step = options.step_deg;
  for (int pass = 0; pass < kPasses; ++pass) {
    const cv::Mat turned = fit.Turned(deg);
    // Half a reduced pixel each way: the parabola's three points.
    for (const cv::Point2d axis : {cv::Point2d(0.5 * k, 0), cv::Point2d(0, 0.5 * k)}) {
      const double at = fit.Cost(turned, fit.Seen(read.displacement));
      const double before = fit.Cost(turned, fit.Seen(read.displacement - axis));
      const double after = fit.Cost(turned, fit.Seen(read.displacement + axis));
      read.displacement += std::clamp(Vertex(before, at, after), -1.0, 1.0) * axis;
    }
    const cv::Point2d moved = read.displacement - displacement;
    if (std::abs(moved.x) > kRefineReachPx || std::abs(moved.y) > kRefineReachPx) {
      return std::nullopt;  // the patch is not near where the search saw it
    }
    step *= 0.5;
    deg = BestAngle(fit, fit.Seen(read.displacement), deg - 2 * step, step, 5);
  }
  read.roll_rad = deg * kRadPerDeg;
  return read;
}

cv::Mat TurnedPlane(const cv::Mat& plane, const cv::Point2d& centre, double roll_deg) {
  // getRotationMatrix2D turns counter-clockwise on the screen for a positive angle (y down):
  // content from +x towards −y. Ours is +x towards +y, hence −roll_deg.
  cv::Mat turned;
  cv::warpAffine(
      plane, turned,
      cv::getRotationMatrix2D(
          cv::Point2f(static_cast<float>(centre.x), static_cast<float>(centre.y)), -roll_deg, 1.0),
      plane.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return turned;
}

cv::Point2d CentreDisplacement(const cv::Point2d& displacement, double roll_rad,
                               const cv::Point2d& patch_offset) {
  // Content at r turns to R·r: (R − I)·r ≈ roll·(−r_y, r_x) for a small roll; the exact form
  // costs nothing.
  const double c = std::cos(roll_rad), s = std::sin(roll_rad);
  const cv::Point2d turn((c - 1) * patch_offset.x - s * patch_offset.y,
                         s * patch_offset.x + (c - 1) * patch_offset.y);
  return displacement - turn;
}

}  // namespace kapfix
