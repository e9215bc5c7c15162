#include "common/selection/slice_selection_run.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/selection/slice_selection.hpp"
#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr int kFrames = 21;

std::vector<cv::Mat> Swing() {
  cv::Mat scene = testing::SmoothTexture({360, 300}, 7);
  scene.rowRange(0, 100).setTo(cv::Scalar(128));  // slices 1–2 flat: they must lose
  return testing::SwingFrames(scene, {300, 300}, testing::PendulumPositions(kFrames, 20.0, 40.0));
}

SliceSelectionOptions Options() {
  SliceSelectionOptions options;
  options.search.range = 20;
  return options;
}

const SearchStrategy& Exhaustive() {
  static const auto strategy = MakeSearchStrategy("all", nullptr);
  return *strategy;
}

TEST(SliceSelectionRunTest, FrameByFrameGivesWhatSelectSliceGivesOverStoredFrames) {
  const auto frames = Swing();
  SliceSelectionRun run(frames.front(), Exhaustive(), Options());
  for (std::size_t t = 1; t < frames.size(); ++t) run.AddFrame(frames[t]);
  const SliceSelection live = run.Result(false);
  const SliceSelection stored = SelectSlice(frames, Exhaustive(), Options());
  ASSERT_EQ(live.slices.size(), stored.slices.size());
  for (std::size_t i = 0; i < live.slices.size(); ++i) {
    EXPECT_EQ(live.slices[i].graph.samples, stored.slices[i].graph.samples) << "slice " << i + 1;
    EXPECT_EQ(live.slices[i].dc, stored.slices[i].dc);
    EXPECT_DOUBLE_EQ(live.slices[i].single_shot, stored.slices[i].single_shot);
  }
  EXPECT_EQ(live.ranking, stored.ranking);
  EXPECT_EQ(live.frames_used, kFrames);
}

TEST(SliceSelectionRunTest, GraphsGrowOneSamplePerFrameForEverySlice) {
  const auto frames = Swing();
  SliceSelectionRun run(frames.front(), Exhaustive(), Options());
  run.AddFrame(frames[1]);
  run.AddFrame(frames[2]);
  const auto graphs = run.Graphs();
  ASSERT_EQ(graphs.size(), 9U);
  for (const auto& graph : graphs) EXPECT_EQ(graph.size(), 2U);
  EXPECT_EQ(run.frames_used(), 3);
}

TEST(SliceSelectionRunTest, StoppedEarlyItMatchesSelectSliceWithAFrameDeadline) {
  const auto frames = Swing();
  SliceSelectionRun run(frames.front(), Exhaustive(), Options());
  for (int t = 1; t < 11; ++t) run.AddFrame(frames[static_cast<std::size_t>(t)]);
  const SliceSelection partial = run.Result(true);
  SliceSelectionOptions options = Options();
  options.deadline_frames = 11;
  const SliceSelection stored = SelectSlice(frames, Exhaustive(), options);
  EXPECT_TRUE(partial.deadline_hit);
  EXPECT_TRUE(stored.deadline_hit);
  EXPECT_EQ(partial.frames_used, 11);
  EXPECT_EQ(partial.ranking, stored.ranking);
  EXPECT_EQ(partial.slices[4].graph.samples, stored.slices[4].graph.samples);
}

TEST(SliceSelectionRunTest, RefusesAFrameOfAnotherSize) {
  const auto frames = Swing();
  SliceSelectionRun run(frames.front(), Exhaustive(), Options());
  EXPECT_THROW(run.AddFrame(cv::Mat(200, 300, CV_8UC1, cv::Scalar(0))), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
