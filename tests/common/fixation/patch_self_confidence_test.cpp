#include "common/fixation/patch_self_confidence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/search/search_strategy.hpp"
#include "common/selection/slice_geometry.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

std::shared_ptr<const SearchStrategy> Pyr() {
  std::string error;
  return MakeSearchStrategy("pyr", &error);
}

// aero1.jpg with the band around slice 1's patch (the top one) painted one flat grey, as far as
// the search reaches beyond it: a featureless part of the scene, which matches itself equally
// well at every shift. (A flat patch in a textured frame would stand out all the same.)
cv::Mat PhotoWithAFlatTopSlice(const FixationOptions& options) {
  cv::Mat frame = testing::LoadOpenCvPhoto("aero1.jpg");
  const cv::Rect top = SlicePatch(frame.size(), options.slice_count, 1, options.patch_size);
  const int bottom = std::min(frame.rows, top.br().y + options.search.range + 8);
  frame(cv::Rect(0, 0, frame.cols, bottom)).setTo(cv::Scalar(128, 128, 128));
  return frame;
}

TEST(PatchSelfConfidenceTest, AFeaturelessPatchIsFoundWithoutConfidenceATexturedOneWith) {
  const FixationOptions options;
  const cv::Mat frame = PhotoWithAFlatTopSlice(options);
  EXPECT_LT(PatchSelfConfidence(frame, 1, options, *Pyr()), options.lock_regain_confidence);
  EXPECT_GE(PatchSelfConfidence(frame, options.slice_count, options, *Pyr()),
            options.lock_regain_confidence);
}

TEST(PatchSelfConfidenceTest, ConfidentSliceSkipsAWeakPatchAlongTheRanking) {
  const FixationOptions options;
  const cv::Mat frame = PhotoWithAFlatTopSlice(options);
  EXPECT_EQ(ConfidentSlice(frame, {1, 9, 5}, options, *Pyr()), 9);
  EXPECT_EQ(ConfidentSlice(frame, {5, 1}, options, *Pyr()), 5);  // the first that passes
}

TEST(PatchSelfConfidenceTest, ConfidentSliceKeepsSspsFirstWhenNoPatchPasses) {
  const FixationOptions options;
  const cv::Mat flat(480, 640, CV_8UC3, cv::Scalar(90, 90, 90));
  EXPECT_EQ(ConfidentSlice(flat, {3, 1, 2}, options, *Pyr()), 3);
}

TEST(PatchSelfConfidenceTest, ConfidentSliceBesidesLeavesTheLostSliceOut) {
  const FixationOptions options;
  const cv::Mat frame = PhotoWithAFlatTopSlice(options);
  EXPECT_EQ(ConfidentSliceBesides(frame, {5, 1, 9}, 5, options, *Pyr()), 9);
  EXPECT_EQ(ConfidentSliceBesides(frame, {5}, 5, options, *Pyr()), std::nullopt);
}

TEST(PatchSelfConfidenceTest, AnEmptyRankingIsRefused) {
  const FixationOptions options;
  EXPECT_THROW(ConfidentSlice(PhotoWithAFlatTopSlice(options), {}, options, *Pyr()),
               std::invalid_argument);
}

TEST(PatchSelfConfidenceTest, PatchSelfConfidencesHasEachSlicesInSliceOrder) {
  const FixationOptions options;
  const cv::Mat frame = PhotoWithAFlatTopSlice(options);
  const std::vector<double> confidences = PatchSelfConfidences(frame, options, *Pyr());
  ASSERT_EQ(confidences.size(), static_cast<std::size_t>(options.slice_count));
  for (const int slice : {1, 5, options.slice_count}) {
    EXPECT_DOUBLE_EQ(confidences[static_cast<std::size_t>(slice - 1)],
                     PatchSelfConfidence(frame, slice, options, *Pyr()))
        << slice;
  }
}

TEST(PatchSelfConfidenceTest, NearestConfidentSliceKeepsASliceThatPasses) {
  EXPECT_EQ(NearestConfidentSlice({0.9, 0.5, 0.4, 0.9, 0.9}, 3, 0.4), 3);
}

TEST(PatchSelfConfidenceTest, NearestConfidentSliceTakesTheNearestThatPassesNotTheMostConfident) {
  //                               1    2    3    4    5    6    7
  EXPECT_EQ(NearestConfidentSlice({0.9, 0.1, 0.1, 0.2, 0.1, 0.5, 0.1}, 4, 0.4), 6);
  EXPECT_EQ(NearestConfidentSlice({0.9, 0.1, 0.1, 0.2, 0.1, 0.1, 0.1}, 4, 0.4), 1);
}

TEST(PatchSelfConfidenceTest, NearestConfidentSliceTakesTheMoreConfidentOfTwoEquallyNear) {
  EXPECT_EQ(NearestConfidentSlice({0.1, 0.45, 0.1, 0.6, 0.1}, 3, 0.4), 4);
  EXPECT_EQ(NearestConfidentSlice({0.1, 0.7, 0.1, 0.6, 0.1}, 3, 0.4), 2);
}

TEST(PatchSelfConfidenceTest, NearestConfidentSliceIsNoneWhenNoSlicePasses) {
  EXPECT_EQ(NearestConfidentSlice({0.1, 0.39, 0.0}, 2, 0.4), std::nullopt);
}

TEST(PatchSelfConfidenceTest, NearestConfidentSliceRefusesASliceOutsideTheConfidences) {
  EXPECT_THROW(NearestConfidentSlice({0.5, 0.5}, 3, 0.4), std::invalid_argument);
  EXPECT_THROW(NearestConfidentSlice({0.5, 0.5}, 0, 0.4), std::invalid_argument);
}

TEST(PatchSelfConfidenceTest, FirstConfidentSliceFollowsTheRankingNotTheDistance) {
  //                                  1    2    3    4    5
  const std::vector<double> confidences{0.9, 0.1, 0.1, 0.5, 0.6};
  EXPECT_EQ(FirstConfidentSlice(confidences, {3, 5, 4, 1}, 0.4), 5);
  EXPECT_EQ(FirstConfidentSlice(confidences, {3, 2}, 0.4), std::nullopt);
  EXPECT_THROW(FirstConfidentSlice(confidences, {3, 6}, 0.4), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
