#pragma once

#include <functional>
#include <opencv2/core.hpp>

#include "common/matching/reference_patch.hpp"

namespace kapfix {

// Distance as a function of both shifts (SPEC §1, thesis chapter 3): a (2R+1)×(2R+1) CV_64F
// matrix whose element (R + dy, R + dx) is the SSD at shift (dx, dy), NaN where the shift
// moves sampled pixels out of the frame.
struct ErrorSurface {
  int range = 0;
  cv::Mat distance;  // CV_64F

  double At(int dx, int dy) const { return distance.at<double>(range + dy, range + dx); }
  bool Valid(int dx, int dy) const;
  // Shift of the global minimum (ties: the first in raster order).
  cv::Point ArgMin() const;
};

// Scores every shift; progress(done, total) is called once per row when given.
ErrorSurface ComputeErrorSurface(const ReferencePatch& reference, const cv::Mat& current, int range,
                                 const std::function<void(int, int)>& progress = nullptr);

}  // namespace kapfix
