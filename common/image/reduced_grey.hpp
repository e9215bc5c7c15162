#pragma once

#include <opencv2/core.hpp>

namespace kapfix {

// `plane` (one or three channels, any depth) as one channel of 32-bit floats, the mean of its
// channels, reduced by `k` ≥ 1 (area average) to cols / k × rows / k: reduced pixel i covers
// full-size pixels k·i … k·i + k − 1 when the plane is a multiple of k wide and high (the
// roll reads crop it so; otherwise INTER_AREA spreads the pixels over the smaller size).
cv::Mat ReducedGrey(const cv::Mat& plane, int k);

}  // namespace kapfix
