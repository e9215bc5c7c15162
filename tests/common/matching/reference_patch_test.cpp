#include "common/matching/reference_patch.hpp"

#include <gtest/gtest.h>

#include "common/image/color_channel.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// The definition, written out plainly: Σ over sampled p of (ref[p] − cur[p + shift])².
template <typename T>
std::int64_t NaiveSsd(const cv::Mat& ref, const cv::Mat& cur, const SampleSet& set,
                      cv::Point shift) {
  std::int64_t sum = 0;
  for (const cv::Point& p : set.Points()) {
    const std::int64_t d = static_cast<std::int64_t>(ref.at<T>(p)) - cur.at<T>(p + shift);
    sum += d * d;
  }
  return sum;
}

TEST(ReferencePatchTest, DistanceEqualsTheDefinitionForEverySampling) {
  const cv::Mat ref = testing::SmoothTexture({120, 90}, 1);
  const cv::Mat cur = testing::SmoothTexture({120, 90}, 2);
  for (const SamplingOptions sampling :
       {SamplingOptions{SamplingKind::kAll}, SamplingOptions{SamplingKind::kStatic},
        SamplingOptions{SamplingKind::kRandom, 0.1, 5}}) {
    const SampleSet set({cv::Rect(30, 20, 50, 40)}, sampling);
    const ReferencePatch patch(ref, set);
    for (const cv::Point shift : {cv::Point(0, 0), cv::Point(-30, 7), cv::Point(40, -20)}) {
      EXPECT_EQ(patch.Distance(cur, shift), NaiveSsd<std::uint8_t>(ref, cur, set, shift))
          << ToString(sampling) << " at " << shift;
    }
  }
}

TEST(ReferencePatchTest, SumOfChannelsUsesSixteenBitArithmetic) {
  cv::Mat ref_bgr(40, 40, CV_8UC3, cv::Scalar(250, 250, 250));
  cv::Mat cur_bgr(40, 40, CV_8UC3, cv::Scalar(0, 0, 0));
  const cv::Mat ref = ExtractChannel(ref_bgr, ColorChannel::kRgbSum);
  const cv::Mat cur = ExtractChannel(cur_bgr, ColorChannel::kRgbSum);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(10, 10, 20, 20)}, {SamplingKind::kAll}));
  EXPECT_EQ(patch.Distance(cur, {0, 0}), 400LL * 750 * 750);
}

TEST(ReferencePatchTest, IdenticalFramesHaveZeroDistanceAtZeroShift) {
  const cv::Mat ref = testing::SmoothTexture({100, 100}, 3);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(25, 25, 50, 50)}, {SamplingKind::kAll}));
  EXPECT_EQ(patch.Distance(ref, {0, 0}), 0);
  EXPECT_GT(patch.Distance(ref, {3, 0}), 0);
}

TEST(ReferencePatchTest, ShiftsMovingSamplesOutOfTheFrameAreExcluded) {
  // Edge handling: clamped out of the search range, never scored partially.
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 4);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  EXPECT_TRUE(patch.CanShift(ref.size(), {-100, 0}));
  EXPECT_FALSE(patch.CanShift(ref.size(), {-101, 0}));
  EXPECT_TRUE(patch.CanShift(ref.size(), {100, 100}));
  EXPECT_FALSE(patch.CanShift(ref.size(), {101, 0}));
  const auto range = patch.ShiftRangeX(ref.size(), 150);
  EXPECT_EQ(range.first, -100);
  EXPECT_EQ(range.last, 100);
}

TEST(ReferencePatchTest, RefusesSamplesOutsideTheReference) {
  const cv::Mat ref = testing::SmoothTexture({50, 50}, 5);
  EXPECT_THROW(ReferencePatch(ref, SampleSet({cv::Rect(40, 40, 20, 20)}, {SamplingKind::kAll})),
               std::invalid_argument);
}

TEST(ReferencePatchTest, ReadsAnRoiCurrentFrameWithItsOwnStride) {
  const cv::Mat big = testing::SmoothTexture({200, 200}, 6);
  const cv::Mat ref = big(cv::Rect(0, 0, 100, 100)).clone();
  const cv::Mat roi = big(cv::Rect(0, 0, 100, 100));  // same pixels, stride 200
  const SampleSet set({cv::Rect(20, 20, 60, 60)}, {SamplingKind::kRandom, 0.1, 1});
  const ReferencePatch patch(ref, set);
  EXPECT_EQ(patch.Distance(roi, {0, 0}), 0);
  EXPECT_EQ(patch.Distance(roi, {5, -3}), NaiveSsd<std::uint8_t>(ref, roi, set, {5, -3}));
}

}  // namespace
}  // namespace kapfix
