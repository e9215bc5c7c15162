#include "common/matching/error_surface.hpp"

#include <cmath>
#include <limits>

namespace kapfix {

bool ErrorSurface::Valid(int dx, int dy) const {
  if (std::abs(dx) > range || std::abs(dy) > range) return false;
  return !std::isnan(At(dx, dy));
}

cv::Point ErrorSurface::ArgMin() const {
  cv::Point best(0, 0);
  double lowest = std::numeric_limits<double>::infinity();
  for (int dy = -range; dy <= range; ++dy) {
    for (int dx = -range; dx <= range; ++dx) {
      const double d = At(dx, dy);
      if (!std::isnan(d) && d < lowest) {
        lowest = d;
        best = {dx, dy};
      }
    }
  }
  return best;
}

ErrorSurface ComputeErrorSurface(const ReferencePatch& reference, const cv::Mat& current, int range,
                                 const std::function<void(int, int)>& progress) {
  ErrorSurface surface;
  surface.range = range;
  const int side = 2 * range + 1;
  surface.distance = cv::Mat(side, side, CV_64F, std::numeric_limits<double>::quiet_NaN());
  for (int dy = -range; dy <= range; ++dy) {
    for (int dx = -range; dx <= range; ++dx) {
      if (!reference.CanShift(current.size(), {dx, dy})) continue;
      surface.distance.at<double>(range + dy, range + dx) =
          static_cast<double>(reference.Distance(current, {dx, dy}));
    }
    if (progress) progress(dy + range + 1, side);
  }
  return surface;
}

}  // namespace kapfix
