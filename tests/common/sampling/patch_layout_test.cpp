#include "common/sampling/patch_layout.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

TEST(PatchLayoutTest, CentralIsOneCentredSquare) {
  const auto rects = MakePatchLayout(PatchLayout::kCentral, {300, 300}, 100);
  ASSERT_EQ(rects.size(), 1u);
  EXPECT_EQ(rects[0], cv::Rect(100, 100, 100, 100));
}

TEST(PatchLayoutTest, IndividualsAreTheThesisFourPatchesOn300) {
  const auto rects = MakePatchLayout(PatchLayout::kIndividuals, {300, 300}, 100);
  EXPECT_EQ(rects,
            (std::vector<cv::Rect>{
                {50, 50, 50, 50}, {200, 50, 50, 50}, {50, 200, 50, 50}, {200, 200, 50, 50}}));
}

TEST(PatchLayoutTest, MergeAddsACentrePatchTo40PixelCorners) {
  const auto rects = MakePatchLayout(PatchLayout::kMerge, {300, 300}, 100);
  ASSERT_EQ(rects.size(), 5u);
  EXPECT_EQ(rects[0], cv::Rect(40, 40, 40, 40));
  EXPECT_EQ(rects[3], cv::Rect(220, 220, 40, 40));
  EXPECT_EQ(rects[4], cv::Rect(130, 130, 40, 40));
}

TEST(PatchLayoutTest, ScalesToLargerFrames) {
  const auto rects = MakePatchLayout(PatchLayout::kIndividuals, {600, 600}, 100);
  EXPECT_EQ(rects[3], cv::Rect(400, 400, 100, 100));
}

TEST(PatchLayoutTest, RefusesAPatchLargerThanTheFrame) {
  EXPECT_THROW(MakePatchLayout(PatchLayout::kCentral, {80, 80}, 100), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
