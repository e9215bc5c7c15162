#include "common/image/sharpness.hpp"

#include <opencv2/imgproc.hpp>

namespace kapfix {

double LaplacianVariance(const cv::Mat& image, cv::Rect region) {
  if (image.empty()) return 0.0;
  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  } else {
    grey = image;
  }
  cv::Mat laplacian;
  cv::Laplacian(grey, laplacian, CV_64F, 1, 1.0, 0.0, cv::BORDER_REFLECT_101);
  const cv::Rect whole(0, 0, laplacian.cols, laplacian.rows);
  const cv::Rect clipped = region.empty() ? whole : (region & whole);
  if (clipped.empty()) return 0.0;
  cv::Scalar mean, stddev;
  cv::meanStdDev(laplacian(clipped), mean, stddev);
  return stddev[0] * stddev[0];
}

}  // namespace kapfix
