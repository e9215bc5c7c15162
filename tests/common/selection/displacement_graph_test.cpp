#include "common/selection/displacement_graph.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/image/color_channel.hpp"
#include "common/selection/direction_changes.hpp"
#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// Search settings of the swing tests: the swings below move < 20 px per frame.
SearchOptions WholePixelSearch(SearchAxis axis = SearchAxis::kX) {
  SearchOptions options;
  options.axis = axis;
  options.range = 20;
  options.subpixel = false;
  return options;
}

const cv::Rect kCentralPatch(100, 100, 100, 100);

std::unique_ptr<SearchStrategy> Strategy(const std::string& name) {
  return MakeSearchStrategy(name, nullptr);
}

// A strategy that never finds anything but reports a large displacement anyway.
class LostStrategy final : public SearchStrategy {
 public:
  std::string name() const override { return "lost"; }
  SearchResult Search(const ReferencePatch&, const cv::Mat&, const SearchOptions&) const override {
    SearchResult r;
    r.found = false;
    r.shift = {42, 42};
    r.displacement = {42.0, 42.0};
    return r;
  }
};

TEST(DisplacementGraphTest, HasOneSamplePerFramePair) {
  const cv::Mat scene = testing::SmoothTexture({400, 320}, 1);
  const auto frames =
      testing::SwingFrames(scene, {300, 300}, testing::PendulumPositions(12, 20.0, 40.0));
  const DisplacementGraph graph =
      BuildDisplacementGraph(frames, kCentralPatch, {}, *Strategy("all"), WholePixelSearch());
  EXPECT_EQ(graph.samples.size(), 11u);
}

TEST(DisplacementGraphTest, SamplesAreTheContentMotionBetweenConsecutiveFrames) {
  const cv::Mat scene = testing::SmoothTexture({400, 320}, 2);
  const auto positions = testing::PendulumPositions(41, 30.0, 40.0);
  const auto frames = testing::SwingFrames(scene, {300, 300}, positions);
  const DisplacementGraph graph =
      BuildDisplacementGraph(frames, kCentralPatch, {}, *Strategy("all"), WholePixelSearch());
  EXPECT_EQ(graph.samples, testing::PerfectGraph(positions));
}

TEST(DisplacementGraphTest, TracksASwingInARealPhoto) {
  const cv::Mat photo = testing::LoadOpenCvPhoto("aero1.jpg");
  ASSERT_FALSE(photo.empty());
  const cv::Mat plane = ExtractChannel(photo, ColorChannel::kGreen);
  const auto positions = testing::PendulumPositions(41, 40.0, 40.0);
  const auto frames = testing::SwingFrames(plane, {300, 300}, positions);
  // Exhaustive search at the default range: the perfect tracker (h23 is not one, SPEC §2.3).
  SearchOptions options;
  options.subpixel = false;
  const DisplacementGraph graph =
      BuildDisplacementGraph(frames, kCentralPatch, {}, *Strategy("all"), options);
  EXPECT_EQ(graph.samples, testing::PerfectGraph(positions));
}

TEST(DisplacementGraphTest, PerfectTrackerOnASmoothSwingShowsTwoChangesPerPeriod) {
  // 201 frames, period 40: 200 samples, so about 2 · 200 / 40 = 10 direction changes once
  // whole-pixel wobbles are held back by the hysteresis.
  const cv::Mat scene = testing::SmoothTexture({400, 320}, 3);
  const auto frames =
      testing::SwingFrames(scene, {300, 300}, testing::PendulumPositions(201, 30.0, 40.0));
  const DisplacementGraph graph =
      BuildDisplacementGraph(frames, kCentralPatch, {}, *Strategy("pyr"), WholePixelSearch());
  EXPECT_NEAR(CountDirectionChanges(graph.samples, 1.5), 10, 1);
}

TEST(DisplacementGraphTest, SearchAlongYReadsTheVerticalMotion) {
  const cv::Mat scene = testing::SmoothTexture({320, 400}, 4);
  const auto positions = testing::PendulumPositions(21, 20.0, 40.0);
  const auto frames = testing::SwingFrames(scene, {300, 300}, positions, /*along_x=*/false);
  const DisplacementGraph graph = BuildDisplacementGraph(
      frames, kCentralPatch, {}, *Strategy("all"), WholePixelSearch(SearchAxis::kY));
  EXPECT_EQ(graph.samples, testing::PerfectGraph(positions));
}

TEST(DisplacementGraphTest, SearchAlongBothAxesReportsTheXComponent) {
  const cv::Mat scene = testing::SmoothTexture({400, 320}, 5, 6.0);
  const auto positions = testing::PendulumPositions(11, 20.0, 40.0);
  const auto frames = testing::SwingFrames(scene, {300, 300}, positions);
  const DisplacementGraph graph = BuildDisplacementGraph(
      frames, kCentralPatch, {}, *Strategy("all"), WholePixelSearch(SearchAxis::kBoth));
  EXPECT_EQ(graph.samples, testing::PerfectGraph(positions));
}

TEST(DisplacementGraphTest, SubpixelSamplesKeepTheFractionalPart) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 6, 5.0);
  cv::Mat moved;
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, 3.3, 0, 1, 0);
  cv::warpAffine(ref, moved, m, ref.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  SearchOptions options = WholePixelSearch();
  const DisplacementGraph whole =
      BuildDisplacementGraph({ref, moved}, kCentralPatch, {}, *Strategy("all"), options);
  options.subpixel = true;
  const DisplacementGraph sub =
      BuildDisplacementGraph({ref, moved}, kCentralPatch, {}, *Strategy("all"), options);
  EXPECT_EQ(whole.samples.at(0), 3.0);
  EXPECT_NEAR(sub.samples.at(0), 3.3, 0.12);
}

TEST(DisplacementGraphTest, AFrameWhereNothingIsFoundGivesAZeroSample) {
  const cv::Mat plane = testing::SmoothTexture({300, 300}, 7);
  const DisplacementGraph graph =
      BuildDisplacementGraph({plane, plane, plane}, kCentralPatch, {}, LostStrategy(), {});
  EXPECT_EQ(graph.samples, (std::vector<double>{0.0, 0.0}));
}

TEST(DisplacementGraphTest, ReportsProgressAfterEachSample) {
  const cv::Mat plane = testing::SmoothTexture({300, 300}, 8);
  std::vector<std::pair<int, int>> calls;
  BuildDisplacementGraph({plane, plane, plane, plane}, kCentralPatch, {}, *Strategy("h23"),
                         WholePixelSearch(),
                         [&](int done, int total) { calls.emplace_back(done, total); });
  EXPECT_EQ(calls, (std::vector<std::pair<int, int>>{{1, 3}, {2, 3}, {3, 3}}));
}

TEST(DisplacementGraphTest, RefusesFramesOfDifferentSizes) {
  const cv::Mat a = testing::SmoothTexture({300, 300}, 9);
  const cv::Mat b = testing::SmoothTexture({300, 299}, 9);
  EXPECT_THROW(BuildDisplacementGraph({a, b}, kCentralPatch, {}, *Strategy("all"), {}),
               std::invalid_argument);
}

TEST(DisplacementGraphTest, RefusesAPatchOutsideTheFrame) {
  const cv::Mat a = testing::SmoothTexture({300, 300}, 10);
  EXPECT_THROW(
      BuildDisplacementGraph({a, a}, cv::Rect(250, 100, 100, 100), {}, *Strategy("all"), {}),
      std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
