// A photo's quality figures: where the reference patch is seen and the sharpness fields (the
// flight's photo means are the flight report's: tests/agent/pipeline/flight_report_test.cpp).
#include "agent/photos/photo_quality.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace kapfix::agent {
namespace {

TEST(PhotoQualityTest, PatchIsSeenWhereTheDisplacementMovedIt) {
  EXPECT_EQ(PatchInFrame(cv::Rect(10, 20, 30, 40), {2.4, -3.6}), cv::Rect(12, 16, 30, 40));
}

// A flat frame with one textured square: the patch over the square is sharper than the frame.
TEST(PhotoQualityTest, PatchSharpnessIsThatOfItsRegion) {
  cv::Mat image(64, 64, CV_8UC1, cv::Scalar(100));
  cv::Mat square = image(cv::Rect(16, 16, 16, 16));
  cv::RNG(7).fill(square, cv::RNG::UNIFORM, 0, 256);
  kapfix::v1::PhotoMetadata metadata;
  FillSharpness(image, cv::Rect(16, 16, 16, 16), &metadata);
  EXPECT_GT(metadata.sharpness_patch(), 2.0F * metadata.sharpness_frame());
  kapfix::v1::PhotoMetadata whole;
  FillSharpness(image, cv::Rect(), &whole);  // no patch: the frame's figure
  EXPECT_FLOAT_EQ(whole.sharpness_patch(), whole.sharpness_frame());
}

}  // namespace
}  // namespace kapfix::agent
