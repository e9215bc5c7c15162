#include "common/selection/patch_size_selection_run.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

std::vector<cv::Mat> Swing() {
  return testing::SwingFrames(testing::SmoothTexture({360, 300}, 11), {300, 300},
                              testing::PendulumPositions(15, 20.0, 40.0));
}

PatchSizeSelectionOptions Options() {
  PatchSizeSelectionOptions options;
  options.search.range = 20;
  return options;
}

const SearchStrategy& Exhaustive() {
  static const auto strategy = MakeSearchStrategy("all", nullptr);
  return *strategy;
}

TEST(PatchSizeSelectionRunTest, FrameByFrameGivesWhatSelectPatchSizeGives) {
  const auto frames = Swing();
  PatchSizeSelectionRun run(frames.front(), Exhaustive(), Options());
  for (std::size_t t = 1; t < frames.size(); ++t) run.AddFrame(frames[t]);
  const PatchSizeSelection live = run.Result();
  const PatchSizeSelection stored = SelectPatchSize(frames, Exhaustive(), Options());
  ASSERT_EQ(live.sizes.size(), stored.sizes.size());
  for (std::size_t i = 0; i < live.sizes.size(); ++i) {
    EXPECT_EQ(live.sizes[i].dc, stored.sizes[i].dc);
    EXPECT_DOUBLE_EQ(live.sizes[i].fft, stored.sizes[i].fft);
  }
  EXPECT_EQ(live.best_size, stored.best_size);
  EXPECT_EQ(run.graphs().front().size(), frames.size() - 1);
}

TEST(PatchSizeSelectionRunTest, TracksAPerfectSwingExactlyWithEverySize) {
  const auto positions = testing::PendulumPositions(15, 20.0, 40.0);
  const auto frames = Swing();
  PatchSizeSelectionOptions options = Options();
  options.search.subpixel = false;  // whole-pixel swing: the integer shifts are exact
  PatchSizeSelectionRun run(frames.front(), Exhaustive(), options);
  for (std::size_t t = 1; t < frames.size(); ++t) run.AddFrame(frames[t]);
  for (const auto& graph : run.graphs()) EXPECT_EQ(graph, testing::PerfectGraph(positions));
}

TEST(PatchSizeSelectionRunTest, RefusesASizeLargerThanTheFrame) {
  PatchSizeSelectionOptions options = Options();
  options.sizes = {400};
  EXPECT_THROW(PatchSizeSelectionRun(Swing().front(), Exhaustive(), options),
               std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
