#include "common/selection/patch_size_selection.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr int kFrames = 41;

PatchSizeSelectionOptions Options() {
  PatchSizeSelectionOptions options;
  options.search.range = 20;
  return options;
}

const SearchStrategy& Exhaustive() {
  static const auto strategy = MakeSearchStrategy("all", nullptr);
  return *strategy;
}

TEST(PatchSizeSelectionTest, FewestDcWins) {
  EXPECT_EQ(BestPatchSize({{50, 30, 1.0}, {100, 20, 9.0}, {150, 10, 5.0}}), 150);
}

TEST(PatchSizeSelectionTest, EqualDcIsBrokenByTheLowerFft) {
  EXPECT_EQ(BestPatchSize({{50, 10, 3.0}, {100, 10, 9.0}, {150, 10, 5.0}}), 50);
}

TEST(PatchSizeSelectionTest, EqualDcAndFftPreferTheSizeClosestTo100) {
  EXPECT_EQ(BestPatchSize({{50, 10, 3.0}, {150, 10, 3.0}, {120, 10, 3.0}}), 120);
}

TEST(PatchSizeSelectionTest, SizesEquallyFarFrom100PreferTheSmaller) {
  EXPECT_EQ(BestPatchSize({{150, 10, 3.0}, {50, 10, 3.0}}), 50);
}

TEST(PatchSizeSelectionTest, ScoresEveryCandidateInOrder) {
  const auto frames = testing::SwingFrames(testing::SmoothTexture({360, 300}, 51), {300, 300},
                                           testing::PendulumPositions(kFrames, 20.0, 40.0));
  const PatchSizeSelection selection = SelectPatchSize(frames, Exhaustive(), Options());
  ASSERT_EQ(selection.sizes.size(), 3u);
  EXPECT_EQ(selection.sizes[0].size, 50);
  EXPECT_EQ(selection.sizes[1].size, 100);
  EXPECT_EQ(selection.sizes[2].size, 150);
}

TEST(PatchSizeSelectionTest, ASmallPatchOnAFeaturelessCentreLoses) {
  // A flat, noisy 90×90 square in the middle of the scene: the 50-px patch sees only noise
  // and jumps about; the larger patches reach the texture around it and follow the swing.
  cv::Mat scene = testing::SmoothTexture({360, 300}, 52);
  scene(cv::Rect(135, 105, 90, 90)).setTo(cv::Scalar(128));
  auto frames =
      testing::SwingFrames(scene, {300, 300}, testing::PendulumPositions(kFrames, 20.0, 40.0));
  testing::AddNoise(frames, 3.0, 53);
  const PatchSizeSelection selection = SelectPatchSize(frames, Exhaustive(), Options());
  EXPECT_NE(selection.best_size, 50);
  EXPECT_GT(selection.sizes[0].dc, selection.sizes[1].dc);
}

TEST(PatchSizeSelectionTest, ReportsProgressAfterEachFrameForAllSizes) {
  const cv::Mat plane = testing::SmoothTexture({300, 300}, 54);
  std::vector<std::pair<int, int>> calls;
  SelectPatchSize({plane, plane, plane}, Exhaustive(), Options(),
                  [&](int done, int total) { calls.emplace_back(done, total); });
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{3, 6}, {6, 6}}));
}

TEST(PatchSizeSelectionTest, RefusesASizeThatDoesNotFitTheFrame) {
  const cv::Mat plane = testing::SmoothTexture({200, 200}, 55);
  PatchSizeSelectionOptions options = Options();
  options.sizes = {100, 201};
  EXPECT_THROW(SelectPatchSize({plane, plane}, Exhaustive(), options), std::invalid_argument);
}

TEST(PatchSizeSelectionTest, OptionsRefuseAnEmptyCandidateList) {
  PatchSizeSelectionOptions options;
  options.sizes.clear();
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("sizes"), std::string::npos);
}

}  // namespace
}  // namespace kapfix
