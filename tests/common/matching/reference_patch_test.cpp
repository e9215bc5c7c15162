#include "common/matching/reference_patch.hpp"

#include <gtest/gtest.h>

#include <any>
#include <opencv2/core.hpp>
#include <vector>

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

TEST(ReferencePatchTest, RgbScoresRedAgainstGreenAsTwoSquaresAPixelWhereTheSumScoresZero) {
  // The thesis's rgb distance is per channel: (255, 0, 0) against (0, 255, 0) differs by 255
  // in two channels. The SSD of B + G + R sees 255 against 255.
  const cv::Mat red(20, 20, CV_8UC3, cv::Scalar(0, 0, 255));  // BGR
  const cv::Mat green(20, 20, CV_8UC3, cv::Scalar(0, 255, 0));
  const SampleSet set({cv::Rect(5, 5, 10, 10)}, {SamplingKind::kAll});
  const ReferencePatch rgb(ExtractChannel(red, ColorChannel::kRgb), set);
  const ReferencePatch sum(ExtractChannel(red, ColorChannel::kRgbSum), set);
  EXPECT_EQ(rgb.Distance(ExtractChannel(green, ColorChannel::kRgb), {0, 0}), 100LL * 2 * 255 * 255);
  EXPECT_EQ(sum.Distance(ExtractChannel(green, ColorChannel::kRgbSum), {0, 0}), 0);
}

TEST(ReferencePatchTest, RgbDistanceOfATwoPixelPatchWorkedByHand) {
  // Reference pixels (1, 2, 3) and (10, 20, 30); under them at shift (1, 0): (4, 0, 3) and
  // (10, 25, 27). Σ = 3² + 2² + 0² + 0² + 5² + 3² = 47.
  cv::Mat ref(1, 3, CV_8UC3, cv::Scalar(0, 0, 0));
  ref.at<cv::Vec3b>(0, 0) = {1, 2, 3};
  ref.at<cv::Vec3b>(0, 1) = {10, 20, 30};
  cv::Mat cur(1, 3, CV_8UC3, cv::Scalar(0, 0, 0));
  cur.at<cv::Vec3b>(0, 1) = {4, 0, 3};
  cur.at<cv::Vec3b>(0, 2) = {10, 25, 27};
  const ReferencePatch patch(ref, SampleSet({cv::Rect(0, 0, 2, 1)}, {SamplingKind::kAll}));
  EXPECT_EQ(patch.Distance(cur, {1, 0}), 47);
}

TEST(ReferencePatchTest, RgbDistanceIsTheSumOfTheThreeChannelsDistancesForEverySampling) {
  // Exact arithmetic on a synthetic image: each channel's SSD computed on its own 8-bit plane
  // (the single-channel path), added, equals the three-channel distance: spans (all), a
  // static pattern and random singles, and a current frame with another stride (an ROI).
  cv::Mat ref;
  cv::Mat cur;
  cv::merge(std::vector<cv::Mat>{testing::SmoothTexture({120, 90}, 11),
                                 testing::SmoothTexture({120, 90}, 12),
                                 testing::SmoothTexture({120, 90}, 13)},
            ref);
  cv::Mat wide;
  cv::merge(std::vector<cv::Mat>{testing::SmoothTexture({160, 90}, 14),
                                 testing::SmoothTexture({160, 90}, 15),
                                 testing::SmoothTexture({160, 90}, 16)},
            wide);
  cur = wide(cv::Rect(0, 0, 120, 90)).clone();
  const cv::Mat roi = wide(cv::Rect(0, 0, 120, 90));  // same pixels, stride 160
  std::vector<cv::Mat> ref_planes;
  std::vector<cv::Mat> cur_planes;
  cv::split(ref, ref_planes);
  cv::split(cur, cur_planes);
  for (const SamplingOptions sampling :
       {SamplingOptions{SamplingKind::kAll}, SamplingOptions{SamplingKind::kStatic},
        SamplingOptions{SamplingKind::kRandom, 0.1, 5}}) {
    const SampleSet set({cv::Rect(30, 20, 50, 40)}, sampling);
    const ReferencePatch patch(ref, set);
    for (const cv::Point shift : {cv::Point(0, 0), cv::Point(-30, 7), cv::Point(40, -20)}) {
      std::int64_t expected = 0;
      for (int c = 0; c < 3; ++c) {
        expected += ReferencePatch(ref_planes[c], set).Distance(cur_planes[c], shift);
      }
      EXPECT_GT(expected, 0);
      EXPECT_EQ(patch.Distance(cur, shift), expected) << ToString(sampling) << " at " << shift;
      EXPECT_EQ(patch.Distance(roi, shift), expected) << ToString(sampling) << " ROI at " << shift;
    }
  }
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

TEST(ReferencePatchTest, DerivedIsBuiltOnceAndSharedByCopies) {
  const ReferencePatch reference(testing::SmoothTexture({64, 64}, 6),
                                 SampleSet({cv::Rect(16, 16, 32, 32)}, {SamplingKind::kAll}));
  int built = 0;
  const auto make = [&] {
    ++built;
    return std::any(1);
  };
  reference.Derived("probe", make);
  reference.Derived("probe", make);
  // Copies share what was derived: the copy is what is tested.
  const ReferencePatch copy = reference;  // NOLINT(performance-unnecessary-copy-initialization)
  copy.Derived("probe", make);
  EXPECT_EQ(built, 1);
  copy.Derived("another key", make);
  EXPECT_EQ(built, 2);
}

}  // namespace
}  // namespace kapfix
