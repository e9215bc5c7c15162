#include "common/image/sharpness.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

TEST(LaplacianVarianceTest, FlatImageHasNone) {
  EXPECT_DOUBLE_EQ(LaplacianVariance(cv::Mat(20, 30, CV_8UC1, cv::Scalar(77))), 0.0);
}

// One bright pixel of 10 in the middle of a 9×9 black image: the Laplacian is −40 there and
// +10 at its four neighbours, 0 elsewhere, so its mean is 0 and its variance
// (40² + 4·10²) / 81.
TEST(LaplacianVarianceTest, ImpulseGivesItsExactVariance) {
  cv::Mat image(9, 9, CV_8UC1, cv::Scalar(0));
  image.at<unsigned char>(4, 4) = 10;
  EXPECT_NEAR(LaplacianVariance(image), (1600.0 + 400.0) / 81.0, 1e-9);
}

// The same impulse seen through a 3×3 region around it: −40, four +10 and four 0 → mean 0,
// variance 2000 / 9; a region far from it sees nothing.
TEST(LaplacianVarianceTest, RegionLimitsTheFigure) {
  cv::Mat image(9, 9, CV_8UC1, cv::Scalar(0));
  image.at<unsigned char>(4, 4) = 10;
  EXPECT_NEAR(LaplacianVariance(image, cv::Rect(3, 3, 3, 3)), 2000.0 / 9.0, 1e-9);
  EXPECT_DOUBLE_EQ(LaplacianVariance(image, cv::Rect(0, 0, 2, 2)), 0.0);
  EXPECT_DOUBLE_EQ(LaplacianVariance(image, cv::Rect(50, 50, 3, 3)), 0.0);  // outside
}

TEST(LaplacianVarianceTest, MotionBlurredPhotoScoresLower) {
  const cv::Mat photo = testing::LoadOpenCvPhoto("aero3.jpg");
  ASSERT_FALSE(photo.empty());
  // A 9 px horizontal smear, as a swing during the exposure leaves.
  const cv::Mat kernel = cv::Mat::ones(1, 9, CV_32F) / 9.0F;
  cv::Mat smeared;
  cv::filter2D(photo, smeared, -1, kernel);
  const double sharp = LaplacianVariance(photo);
  const double blurred = LaplacianVariance(smeared);
  EXPECT_GT(sharp, 0.0);
  EXPECT_LT(blurred, 0.5 * sharp);
}

}  // namespace
}  // namespace kapfix
