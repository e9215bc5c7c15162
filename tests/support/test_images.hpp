#pragma once

#include <gtest/gtest.h>

#include <algorithm>
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

// A `frame`-sized view of an opencv-doc photo centred on the photo's centre, its content turned
// by `roll_deg` about the view's centre (from +x towards +y: clockwise on the screen) and then
// shifted by `shift` [px]: a camera that rolled and moved. BGR. `scale`: the photo enlarged
// about its centre first (as the simulator enlarges a photo smaller than the frame and swing).
inline cv::Mat RolledView(const std::string& name, cv::Size frame, double roll_deg,
                          cv::Point2d shift, double scale = 1.0) {
  const cv::Mat photo = LoadOpenCvPhoto(name);
  const cv::Point2f c(0.5F * static_cast<float>(photo.cols - 1),
                      0.5F * static_cast<float>(photo.rows - 1));
  // OpenCV's angle: +x towards −y
  cv::Mat move = cv::getRotationMatrix2D(c, -roll_deg, scale);
  // Onto a canvas at least the frame's size, the photo's centre on the canvas's centre.
  const cv::Size canvas(std::max(photo.cols, frame.width), std::max(photo.rows, frame.height));
  const cv::Point2f cc(0.5F * static_cast<float>(canvas.width - 1),
                       0.5F * static_cast<float>(canvas.height - 1));
  move.at<double>(0, 2) += shift.x + (cc.x - c.x);
  move.at<double>(1, 2) += shift.y + (cc.y - c.y);
  cv::Mat moved;
  cv::warpAffine(photo, moved, move, canvas, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return moved(cv::Rect(static_cast<int>(cc.x + 0.5F) - frame.width / 2,
                        static_cast<int>(cc.y + 0.5F) - frame.height / 2, frame.width,
                        frame.height))
      .clone();
}

}  // namespace kapfix::testing
