#include "common/selection/slice_selection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "common/selection/single_shot_score.hpp"
#include "common/selection/slice_geometry.hpp"
#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr int kFrames = 41;

// A 300×300 view swinging ±20 px along x with period 40 frames over a smooth texture whose
// top third (rows 0…99, the patches of slices 1 and 2) is flat grey.
std::vector<cv::Mat> FlatTopSwing(double noise_sigma) {
  cv::Mat scene = testing::SmoothTexture({360, 300}, 41);
  scene.rowRange(0, 100).setTo(cv::Scalar(128));
  auto frames =
      testing::SwingFrames(scene, {300, 300}, testing::PendulumPositions(kFrames, 20.0, 40.0));
  if (noise_sigma > 0.0) testing::AddNoise(frames, noise_sigma, 42);
  return frames;
}

std::vector<cv::Mat> TexturedSwing() {
  return testing::SwingFrames(testing::SmoothTexture({360, 300}, 43), {300, 300},
                              testing::PendulumPositions(kFrames, 20.0, 40.0));
}

// Exhaustive within the swing's reach: fast, and never the reason a slice fails.
SliceSelectionOptions Options() {
  SliceSelectionOptions options;
  options.search.range = 20;
  return options;
}

const SearchStrategy& Exhaustive() {
  static const auto strategy = MakeSearchStrategy("all", nullptr);
  return *strategy;
}

TEST(SliceSelectionOptionsTest, DefaultsAreTheThesisAndValid) {
  const SliceSelectionOptions options;
  EXPECT_EQ(options.slice_count, 9);
  EXPECT_EQ(options.patch_size, 100);
  EXPECT_EQ(options.score, SliceScoreKind::kDc);
  std::string error;
  EXPECT_TRUE(options.IsValid(&error)) << error;
}

TEST(SliceSelectionOptionsTest, RefusesZeroSlices) {
  SliceSelectionOptions options;
  options.slice_count = 0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("slice count"), std::string::npos);
}

TEST(SliceSelectionOptionsTest, RefusesANegativeHysteresis) {
  SliceSelectionOptions options;
  options.hysteresis_px = -0.5;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("hysteresis"), std::string::npos);
}

TEST(SliceSelectionOptionsTest, RefusesADeadlineOfOneFrame) {
  SliceSelectionOptions options;
  options.deadline_frames = 1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("deadline"), std::string::npos);
}

TEST(SliceSelectionOptionsTest, RefusesANegativeDeadlineInSeconds) {
  SliceSelectionOptions options;
  options.deadline_seconds = -1.0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("deadline"), std::string::npos);
}

TEST(SliceSelectionTest, ScoresEverySliceInIndexOrder) {
  const SliceSelection selection = SelectSlice(TexturedSwing(), Exhaustive(), Options());
  ASSERT_EQ(selection.slices.size(), 9u);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(selection.slices[i].index, i + 1);
    EXPECT_EQ(selection.slices[i].patch, SlicePatch({300, 300}, 9, i + 1, 100));
    EXPECT_EQ(selection.slices[i].graph.samples.size(), kFrames - 1u);
  }
}

TEST(SliceSelectionTest, BestSliceLeadsAFullRanking) {
  const SliceSelection selection = SelectSlice(TexturedSwing(), Exhaustive(), Options());
  std::vector<int> sorted = selection.ranking;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(selection.best_slice, selection.ranking.front());
}

TEST(SliceSelectionTest, DcDoesNotPickAFlatSliceOfANoisyCamera) {
  // Sensor noise (SPEC §3: σ = 3 grey levels) makes a featureless patch's match jump about,
  // which the DC count sees; the textured slices follow the swing.
  // Whole-pixel tracking, as the thesis's: with the sub-pixel part, noise wobbles the
  // textured slices' graphs too and the plain count no longer separates them (dc-hyst does).
  SliceSelectionOptions options = Options();
  options.search.subpixel = false;
  const SliceSelection selection = SelectSlice(FlatTopSwing(3.0), Exhaustive(), options);
  EXPECT_GT(selection.best_slice, 2);
  EXPECT_GT(selection.slices[0].dc, 2 * selection.slices[selection.best_slice - 1].dc);
}

TEST(SliceSelectionTest, EquallyGoodSlicesResolveToTheCentralSlice) {
  // A whole-pixel perfect tracker gives every slice of a uniform texture the same graph, so
  // DC and FFT tie and closeness to the centre decides.
  SliceSelectionOptions options = Options();
  options.search.subpixel = false;
  const SliceSelection selection = SelectSlice(TexturedSwing(), Exhaustive(), options);
  EXPECT_EQ(selection.slices[0].dc, selection.slices[4].dc);
  EXPECT_EQ(selection.slices[0].fft, selection.slices[4].fft);
  EXPECT_EQ(selection.best_slice, 5);
}

TEST(SliceSelectionTest, SingleShotDoesNotPickAFlatSliceEvenWithoutNoise) {
  SliceSelectionOptions options = Options();
  options.score = SliceScoreKind::kSingleShot;
  const SliceSelection selection = SelectSlice(FlatTopSwing(0.0), Exhaustive(), options);
  EXPECT_EQ(selection.slices[0].single_shot, 0.0);
  EXPECT_GT(selection.best_slice, 2);
}

TEST(SliceSelectionTest, SingleShotIsScoredOnTheFirstFrame) {
  const auto frames = TexturedSwing();
  const SliceSelectionOptions options = Options();
  const SliceSelection selection = SelectSlice(frames, Exhaustive(), options);
  for (const SliceScore& slice : selection.slices) {
    EXPECT_EQ(
        slice.single_shot,
        ComputeSingleShotScore(frames[0], slice.patch, options.sampling, options.search).score);
  }
}

TEST(SliceSelectionTest, WithoutADeadlineEveryFrameIsUsed) {
  const SliceSelection selection = SelectSlice(TexturedSwing(), Exhaustive(), Options());
  EXPECT_EQ(selection.frames_used, kFrames);
  EXPECT_FALSE(selection.deadline_hit);
}

TEST(SliceSelectionTest, AFrameDeadlineStopsWithWhatItHas) {
  SliceSelectionOptions options = Options();
  options.deadline_frames = 10;
  const SliceSelection selection = SelectSlice(TexturedSwing(), Exhaustive(), options);
  EXPECT_TRUE(selection.deadline_hit);
  EXPECT_EQ(selection.frames_used, 10);
  for (const SliceScore& slice : selection.slices) EXPECT_EQ(slice.graph.samples.size(), 9u);
}

TEST(SliceSelectionTest, ATimeDeadlineStillMeasuresTheFirstPair) {
  SliceSelectionOptions options = Options();
  options.deadline_seconds = 1e-9;
  const SliceSelection selection = SelectSlice(TexturedSwing(), Exhaustive(), options);
  EXPECT_TRUE(selection.deadline_hit);
  EXPECT_EQ(selection.frames_used, 2);
  for (const SliceScore& slice : selection.slices) EXPECT_EQ(slice.graph.samples.size(), 1u);
}

TEST(SliceSelectionTest, ReportsProgressAfterEachFramePair) {
  SliceSelectionOptions options = Options();
  options.deadline_frames = 5;
  std::vector<std::pair<int, int>> calls;
  SelectSlice(TexturedSwing(), Exhaustive(), options,
              [&](int done, int total) { calls.emplace_back(done, total); });
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{1, 4}, {2, 4}, {3, 4}, {4, 4}}));
}

TEST(SliceSelectionTest, RefusesASingleFrame) {
  const auto frames = TexturedSwing();
  EXPECT_THROW(SelectSlice({frames[0]}, Exhaustive(), Options()), std::invalid_argument);
}

TEST(SliceSelectionTest, RefusesAPatchLargerThanTheFrame) {
  SliceSelectionOptions options = Options();
  options.patch_size = 301;
  EXPECT_THROW(SelectSlice(TexturedSwing(), Exhaustive(), options), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
