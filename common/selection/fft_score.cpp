#include "common/selection/fft_score.hpp"

#include <cmath>
#include <opencv2/core.hpp>

namespace kapfix {

double FftScore(const std::vector<double>& graph) {
  const int n = static_cast<int>(graph.size());
  if (n < 2) return 0.0;
  cv::Mat signal(1, n, CV_64F);
  for (int i = 0; i < n; ++i) signal.at<double>(0, i) = graph[static_cast<std::size_t>(i)];
  cv::Mat spectrum;
  cv::dft(signal, spectrum, cv::DFT_COMPLEX_OUTPUT);
  double sum = 0.0;
  for (int k = 1; k <= n / 2; ++k) {
    const cv::Vec2d bin = spectrum.at<cv::Vec2d>(0, k);
    sum += std::hypot(bin[0], bin[1]);
  }
  return sum;
}

}  // namespace kapfix
