#include "common/matching/error_curve.hpp"

#include <gtest/gtest.h>

#include "common/matching/error_surface.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

TEST(ErrorCurveTest, MinimumSitsAtTheTrueShift) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 11);
  const cv::Mat cur = testing::Translated(ref, 17, 0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  const ErrorCurve curve = ComputeErrorCurve(patch, cur, true, 100);
  ASSERT_EQ(curve.shifts.size(), 201u);
  EXPECT_EQ(curve.shifts[curve.ArgMin()], 17);
  EXPECT_EQ(curve.distances[curve.ArgMin()], 0);
}

TEST(ErrorCurveTest, CoversOnlyShiftsInsideTheFrame) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 12);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(20, 100, 100, 100)}, {SamplingKind::kAll}));
  const ErrorCurve curve = ComputeErrorCurve(patch, ref, true, 100);
  EXPECT_EQ(curve.shifts.front(), -20);
  EXPECT_EQ(curve.shifts.back(), 100);
}

TEST(ErrorSurfaceTest, MinimumSitsAtTheTrueTwoDimensionalShift) {
  const cv::Mat ref = testing::SmoothTexture({120, 120}, 13);
  const cv::Mat cur = testing::Translated(ref, -6, 9);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(35, 35, 50, 50)}, {SamplingKind::kAll}));
  int rows = 0;
  const ErrorSurface surface = ComputeErrorSurface(patch, cur, 20, [&](int, int) { ++rows; });
  EXPECT_EQ(rows, 41);
  EXPECT_EQ(surface.ArgMin(), cv::Point(-6, 9));
  EXPECT_EQ(surface.At(-6, 9), 0.0);
}

TEST(ErrorSurfaceTest, MarksShiftsOutsideTheFrameInvalid) {
  const cv::Mat ref = testing::SmoothTexture({100, 100}, 14);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(10, 40, 20, 20)}, {SamplingKind::kAll}));
  const ErrorSurface surface = ComputeErrorSurface(patch, ref, 15);
  EXPECT_FALSE(surface.Valid(-11, 0));
  EXPECT_TRUE(surface.Valid(-10, 0));
}

}  // namespace
}  // namespace kapfix
