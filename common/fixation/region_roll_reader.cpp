#include "common/fixation/region_roll_reader.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "common/image/reduced_grey.hpp"

namespace kapfix {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace

bool RegionRollOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (grow_px < 0) return fail("roll region growth must be ≥ 0 px");
  if (reduce < 1 || reduce > 8) return fail("roll region reduction must be 1…8");
  if (!(max_change_deg > 0 && max_change_deg <= 45)) {
    return fail("roll region's largest change must be in (0, 45] deg");
  }
  if (!(min_correlation >= 0 && min_correlation < 1)) {
    return fail("roll region's least correlation must be in [0, 1)");
  }
  if (iterations < 1) return fail("roll region alignment needs at least one iteration");
  return true;
}

RegionRollReader::RegionRollReader(const cv::Mat& reference_plane, const cv::Rect& patch,
                                   RegionRollOptions options)
    : options_(options),
      centre_(patch.x + 0.5 * (patch.width - 1), patch.y + 0.5 * (patch.height - 1)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("RegionRollReader: " + error);
  // As far around the patch as asked, within the frame (a patch on the frame's edge gets a
  // region reaching away from it), on the reduced grid; at least twice the patch's area, or
  // there is no region to read.
  const int k = options_.reduce;
  const cv::Rect frame(0, 0, reference_plane.cols - reference_plane.cols % k,
                       reference_plane.rows - reference_plane.rows % k);
  const int g = options_.grow_px;
  cv::Rect wanted(patch.x - g, patch.y - g, patch.width + 2 * g, patch.height + 2 * g);
  wanted &= frame;
  const cv::Point tl((wanted.x + k - 1) / k * k, (wanted.y + k - 1) / k * k);
  const cv::Point br(wanted.br().x / k * k, wanted.br().y / k * k);
  if (br.x - tl.x < 8 * k || br.y - tl.y < 8 * k) return;
  const cv::Rect rect(tl, br);
  if (rect.area() < 2 * patch.area()) return;
  region_rect_ = rect;
  region_ = ReducedGrey(reference_plane(rect), k);
}

std::optional<RegionRoll> RegionRollReader::Read(const cv::Mat& plane,
                                                 const cv::Point2d& displacement,
                                                 double start_deg) const {
  if (region_.empty()) return std::nullopt;
  const int k = options_.reduce;
  // The frame around where the region is expected, reduced on the reference's grid (a
  // multiple of k from the frame's corner), with a quarter of the region each side for the
  // turn and the shift the alignment may find.
  const int margin = k * ((std::max(region_rect_.width, region_rect_.height) / 4 + k - 1) / k);
  const cv::Rect frame(0, 0, plane.cols - plane.cols % k, plane.rows - plane.rows % k);
  const cv::Rect around =
      cv::Rect(region_rect_.x + static_cast<int>(std::floor(displacement.x / k)) * k - margin,
               region_rect_.y + static_cast<int>(std::floor(displacement.y / k)) * k - margin,
               region_rect_.width + 2 * margin, region_rect_.height + 2 * margin) &
      frame;
  if (around.width < region_.cols * k / 2 || around.height < region_.rows * k / 2) {
    return std::nullopt;  // the region has left the frame
  }
  const cv::Mat seen = ReducedGrey(plane(around), k);
  // [reduced px] where `seen` lies in the frame (`around` is on the reduced grid)
  const cv::Point2d corner(cv::Point(around.x / k, around.y / k));
  // Reduced pixel u of the region is full-size a + k·u (its centre), of the frame h + k·w.
  // Full size, the frame sees x at R·(x − c) + c + d, so the warp from region to frame pixels
  // is w = R·u + (R·(a − c) + c + d − h) / k.
  const double h = 0.5 * (k - 1);
  const cv::Point2d a(region_rect_.x + h, region_rect_.y + h);
  const auto offset = [&](const cv::Matx22d& r, const cv::Point2d& d) {
    const cv::Point2d ac = a - centre_;
    return cv::Point2d(r(0, 0) * ac.x + r(0, 1) * ac.y, r(1, 0) * ac.x + r(1, 1) * ac.y) + centre_ +
           d - cv::Point2d(h, h);
  };
  const double start = start_deg / kDegPerRad;
  const cv::Matx22d r0(std::cos(start), -std::sin(start), std::sin(start), std::cos(start));
  const cv::Point2d b0 = offset(r0, displacement) / k - corner;
  cv::Mat warp = (cv::Mat_<float>(2, 3) << r0(0, 0), r0(0, 1), b0.x, r0(1, 0), r0(1, 1), b0.y);
  RegionRoll read;
  try {
    read.correlation =
        cv::findTransformECC(region_, seen, warp, cv::MOTION_EUCLIDEAN,
                             cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                              options_.iterations, 1e-4),
                             cv::noArray(), 3);
  } catch (const cv::Exception&) {
    return std::nullopt;  // the alignment diverged (or the region left the frame entirely)
  }
  const cv::Matx22d r(warp.at<float>(0, 0), warp.at<float>(0, 1), warp.at<float>(1, 0),
                      warp.at<float>(1, 1));
  read.roll_deg = std::atan2(r(1, 0), r(0, 0)) * kDegPerRad;
  // d from the warp's shift b: k·b = R·(a − c) + c + d − h.
  const cv::Point2d kb = (cv::Point2d(warp.at<float>(0, 2), warp.at<float>(1, 2)) + corner) * k;
  read.displacement = kb - (offset(r, {0, 0}));
  if (!std::isfinite(read.correlation) || read.correlation < options_.min_correlation ||
      std::abs(read.roll_deg - start_deg) > options_.max_change_deg) {
    return std::nullopt;
  }
  return read;
}

}  // namespace kapfix
