#include "common/image/reduced_grey.hpp"

#include <opencv2/imgproc.hpp>

namespace kapfix {

cv::Mat ReducedGrey(const cv::Mat& plane, int k) {
  cv::Mat grey;
  plane.convertTo(grey, CV_32F);
  if (grey.channels() == 3) cv::transform(grey, grey, cv::Matx13f(1.F / 3, 1.F / 3, 1.F / 3));
  if (k == 1) return grey;
  cv::Mat small;
  cv::resize(grey, small, cv::Size(grey.cols / k, grey.rows / k), 0, 0, cv::INTER_AREA);
  return small;
}

}  // namespace kapfix
