#pragma once

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

namespace kapfix::testing {

// Path of a Debian opencv-doc photo (installed by deploy/setup-debian.sh).
inline std::string OpenCvDataPath(const std::string& name) {
  return std::string(KAPFIX_OPENCV_DATA_DIR) + "/" + name;
}

// Loads an opencv-doc photo as BGR; the calling test fails (not skips) when it is missing,
// because the set-up script installs it.
inline cv::Mat LoadOpenCvPhoto(const std::string& name) {
  cv::Mat image = cv::imread(OpenCvDataPath(name), cv::IMREAD_COLOR);
  EXPECT_FALSE(image.empty()) << "missing " << OpenCvDataPath(name)
                              << " (run deploy/setup-debian.sh: package opencv-doc)";
  return image;
}

// Smooth, non-repetitive synthetic texture (sum of blurred random noise), for exact tests.
inline cv::Mat SmoothTexture(cv::Size size, int seed, double blur_sigma = 3.0) {
  cv::Mat noise(size, CV_8UC1);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::Mat blurred;
  cv::GaussianBlur(noise, blurred, cv::Size(0, 0), blur_sigma);
  cv::normalize(blurred, blurred, 0, 255, cv::NORM_MINMAX);
  return blurred;
}

// `image` moved by (dx, dy): content at p in `image` appears at p + (dx, dy).
inline cv::Mat Translated(const cv::Mat& image, int dx, int dy) {
  cv::Mat moved;
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::warpAffine(image, moved, m, image.size(), cv::INTER_NEAREST, cv::BORDER_REFLECT);
  return moved;
}

}  // namespace kapfix::testing
