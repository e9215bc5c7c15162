#include "common/matching/error_curve.hpp"

#include <cstdlib>

namespace kapfix {

int ErrorCurve::ArgMin() const {
  int best = -1;
  for (int i = 0; i < static_cast<int>(distances.size()); ++i) {
    if (best < 0 || distances[i] < distances[best] ||
        (distances[i] == distances[best] && std::abs(shifts[i]) < std::abs(shifts[best]))) {
      best = i;
    }
  }
  return best;
}

ErrorCurve ComputeErrorCurve(const ReferencePatch& reference, const cv::Mat& current, bool along_x,
                             int range) {
  ErrorCurve curve;
  curve.along_x = along_x;
  const auto interval = along_x ? reference.ShiftRangeX(current.size(), range)
                                : reference.ShiftRangeY(current.size(), range);
  if (!reference.CanShift(current.size(), {0, 0})) return curve;
  for (int s = interval.first; s <= interval.last; ++s) {
    curve.shifts.push_back(s);
    curve.distances.push_back(
        reference.Distance(current, along_x ? cv::Point(s, 0) : cv::Point(0, s)));
  }
  return curve;
}

}  // namespace kapfix
