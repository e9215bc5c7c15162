#include "common/selection/slice_geometry.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "common/sampling/patch_layout.hpp"

namespace kapfix {
namespace {

std::string ErrorOf(cv::Size frame, int count, int index, int size) {
  try {
    SlicePatch(frame, count, index, size);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SliceGeometryTest, CentralSliceOfNineIsTheCentralPatch) {
  EXPECT_EQ(SlicePatch({300, 300}, 9, 5, 100), cv::Rect(100, 100, 100, 100));
  EXPECT_EQ(SlicePatch({301, 301}, 9, 5, 100),
            MakePatchLayout(PatchLayout::kCentral, {301, 301}, 100).front());
}

TEST(SliceGeometryTest, PatchSitsOnTheSlicesVerticalCentreAndTheFramesHorizontalCentre) {
  // Slice 3 of 9 in a 900-px-tall frame spans rows 200…299, centre 250.
  EXPECT_EQ(SlicePatch({400, 900}, 9, 3, 50), cv::Rect(175, 225, 50, 50));
}

TEST(SliceGeometryTest, OuterSlicesAreClampedInsideTheFrame) {
  // A 100-px patch does not fit a 33-px slice: slices 1 and 2 share the top patch.
  EXPECT_EQ(SlicePatch({300, 300}, 9, 1, 100), cv::Rect(100, 0, 100, 100));
  EXPECT_EQ(SlicePatch({300, 300}, 9, 2, 100), cv::Rect(100, 0, 100, 100));
  EXPECT_EQ(SlicePatch({300, 300}, 9, 9, 100), cv::Rect(100, 200, 100, 100));
}

TEST(SliceGeometryTest, RefusesAnIndexOutsideTheSlices) {
  EXPECT_NE(ErrorOf({300, 300}, 9, 0, 100).find("slice index"), std::string::npos);
  EXPECT_NE(ErrorOf({300, 300}, 9, 10, 100).find("slice index"), std::string::npos);
}

TEST(SliceGeometryTest, RefusesANonPositiveSliceCount) {
  EXPECT_NE(ErrorOf({300, 300}, 0, 1, 100).find("slice count"), std::string::npos);
}

TEST(SliceGeometryTest, RefusesAPatchThatDoesNotFitTheFrame) {
  EXPECT_NE(ErrorOf({300, 200}, 9, 5, 201).find("patch size"), std::string::npos);
  EXPECT_NE(ErrorOf({300, 200}, 9, 5, 0).find("patch size"), std::string::npos);
}

TEST(SliceGeometryTest, RefusesAnEmptyFrame) {
  EXPECT_NE(ErrorOf({0, 300}, 9, 5, 100).find("empty frame"), std::string::npos);
}

}  // namespace
}  // namespace kapfix

namespace kapfix {
namespace {

TEST(SliceGroupsTest, ThreeHundredPixelFrameMergesTheOuterPairs) {
  // 9 slices of 33 px under a 100-px patch: slices 1 and 2 both clamp to the top, 8 and 9 to
  // the bottom.
  const auto groups = SliceGroups({300, 300}, 9, 100);
  ASSERT_EQ(groups.size(), 7U);
  EXPECT_EQ(groups.front(), (std::vector<int>{1, 2}));
  EXPECT_EQ(groups.back(), (std::vector<int>{8, 9}));
}

TEST(SliceGroupsTest, UnclampedHeightGivesEverySliceItsOwnPatch) {
  const int height = UnclampedSliceHeight(9, 100);
  EXPECT_EQ(height, 900);
  EXPECT_EQ(SliceGroups({300, height}, 9, 100).size(), 9U);
  // The top slice's patch starts at the top of the frame without being clamped there.
  EXPECT_EQ(SlicePatch({300, height}, 9, 1, 100).y, 0);
  EXPECT_EQ(SlicePatch({300, height}, 9, 2, 100).y, 100);
}

}  // namespace
}  // namespace kapfix
