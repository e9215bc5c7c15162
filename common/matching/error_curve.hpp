#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "common/matching/reference_patch.hpp"

namespace kapfix {

// Distance as a function of the shift along one axis (SPEC §1), for every shift in
// [−range, +range] that keeps the sampled pixels inside the frame.
struct ErrorCurve {
  bool along_x = true;
  std::vector<int> shifts;              // [px]
  std::vector<std::int64_t> distances;  // SSD at each shift

  // Index of the lowest distance (ties: the shift nearest 0); −1 when empty.
  int ArgMin() const;
};

ErrorCurve ComputeErrorCurve(const ReferencePatch& reference, const cv::Mat& current, bool along_x,
                             int range);

}  // namespace kapfix
