#include "common/matching/sliding_ssd.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <vector>

#include "common/matching/reference_patch.hpp"

namespace kapfix {
namespace {

// Full-range noise: squares and products near their extremes, where an overflow would show.
cv::Mat Noise(cv::Size size, int seed) {
  cv::Mat m(size, CV_8UC1);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  return m;
}

std::int64_t DirectSsd(const cv::Mat& block, const cv::Mat& current, cv::Point at) {
  std::int64_t sum = 0;
  for (int y = 0; y < block.rows; ++y) {
    for (int x = 0; x < block.cols; ++x) {
      const std::int64_t d = static_cast<std::int64_t>(block.at<std::uint8_t>(y, x)) -
                             current.at<std::uint8_t>(at.y + y, at.x + x);
      sum += d * d;
    }
  }
  return sum;
}

void ExpectEqualsDirect(const cv::Mat& block, const cv::Mat& current, cv::Point first, int count,
                        bool along_x) {
  const SlidingSsd sliding(block);
  std::vector<std::int64_t> out(static_cast<std::size_t>(count), -1);
  sliding.Score(current, first, count, along_x, out.data());
  for (int i = 0; i < count; ++i) {
    const cv::Point at = first + (along_x ? cv::Point(i, 0) : cv::Point(0, i));
    const std::int64_t direct = DirectSsd(block, current, at);
    ASSERT_EQ(out[static_cast<std::size_t>(i)], direct)
        << block.size() << (along_x ? " along x at " : " along y at ") << at;
    ASSERT_EQ(sliding.At(current, at), direct) << block.size() << " single position at " << at;
  }
}

TEST(SlidingSsdTest, EqualsTheDirectSsdForWidthsAroundTheVectorLength) {
  const cv::Mat current = Noise({160, 120}, 1);
  for (const int width : {1, 15, 16, 17, 25, 100}) {
    const cv::Mat block = Noise({width, 13}, width);
    ExpectEqualsDirect(block, current, {0, 3}, current.cols - width + 1, true);
    ExpectEqualsDirect(block, current, {current.cols - width, 0}, current.rows - 13 + 1, false);
  }
}

TEST(SlidingSsdTest, ReadsNothingPastTheEndOfAnExactlySizedPlane) {
  // The block's last row meets the plane's last row at its right edge: the padded read would
  // run past the buffer, so those rows take the exact-width loop (ASan checks the reads).
  const cv::Mat current = Noise({40, 30}, 2);
  const cv::Mat block = Noise({25, 10}, 3);
  ExpectEqualsDirect(block, current, {0, 20}, 16, true);
  ExpectEqualsDirect(block, current, {15, 0}, 21, false);
}

TEST(SlidingSsdTest, ReadsAnRoiWithItsOwnStride) {
  const cv::Mat parent = Noise({200, 100}, 4);
  const cv::Mat current = parent(cv::Rect(37, 11, 120, 80));
  const cv::Mat block = Noise({50, 40}, 5);
  ExpectEqualsDirect(block, current, {0, 40}, 71, true);
  ExpectEqualsDirect(block, current, {70, 0}, 41, false);
}

TEST(SlidingSsdTest, IsOfferedOnlyForDenseEightBitReferences) {
  const cv::Mat plane = Noise({100, 100}, 6);
  const ReferencePatch dense(plane, SampleSet({cv::Rect(20, 20, 50, 50)}, {SamplingKind::kAll}));
  const ReferencePatch sparse(plane,
                              SampleSet({cv::Rect(20, 20, 50, 50)}, {SamplingKind::kRandom, 0.1}));
  cv::Mat wide;
  plane.convertTo(wide, CV_16U);
  const ReferencePatch deep(wide, SampleSet({cv::Rect(20, 20, 50, 50)}, {SamplingKind::kAll}));
  const SlidingSsd* sliding = SlidingSsd::ForReference(dense);
  ASSERT_NE(sliding, nullptr);
  EXPECT_EQ(sliding->size(), cv::Size(50, 50));
  EXPECT_EQ(SlidingSsd::ForReference(dense), sliding);  // built once
  EXPECT_EQ(SlidingSsd::ForReference(sparse), nullptr);
  EXPECT_EQ(SlidingSsd::ForReference(deep), nullptr);
}

}  // namespace
}  // namespace kapfix
