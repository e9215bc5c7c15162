// A photo's quality figures: where the reference patch is seen, the sharpness fields, and the
// flight's photo means for the benchmark.
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

TEST(PhotoQualityTest, FiguresAreTheMeansOverThePhotos) {
  std::vector<kapfix::v1::PhotoMetadata> photos(2);
  photos[0].set_view_speed_px_per_frame(1.0F);
  photos[0].set_residual_offset_px(2.0F);
  photos[0].set_sharpness_frame(100.0F);
  photos[0].set_shutter_wait_s(0.5F);
  photos[1].set_view_speed_px_per_frame(3.0F);
  photos[1].set_residual_offset_px(4.0F);
  photos[1].set_sharpness_frame(300.0F);
  photos[1].set_shutter_wait_s(0.0F);
  photos[1].set_lock_lost(true);
  const PhotoFigures f = ComputePhotoFigures(photos);
  EXPECT_EQ(f.photos, 2u);
  EXPECT_DOUBLE_EQ(f.view_speed_px_mean, 2.0);
  EXPECT_DOUBLE_EQ(f.offset_px_mean, 3.0);
  EXPECT_DOUBLE_EQ(f.sharpness_mean, 200.0);
  EXPECT_DOUBLE_EQ(f.wait_s_mean, 0.25);
  EXPECT_DOUBLE_EQ(f.lock_lost_share, 0.5);
}

TEST(PhotoQualityTest, NoPhotosHaveNoMeans) {
  const PhotoFigures f = ComputePhotoFigures({});
  EXPECT_EQ(f.photos, 0u);
  EXPECT_TRUE(std::isnan(f.view_speed_px_mean));
}

}  // namespace
}  // namespace kapfix::agent
