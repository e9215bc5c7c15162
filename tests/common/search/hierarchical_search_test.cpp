#include "common/search/hierarchical_search.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

const HierarchicalPreset& Preset(const std::string& name) {
  for (const auto& p : HierarchicalPresets()) {
    if (p.name == name) return p;
  }
  throw std::runtime_error("no preset " + name);
}

using Levels = std::array<std::vector<int>, 3>;

TEST(HierarchicalPresetTest, H23MatchesThesisTable45) {
  EXPECT_EQ(Preset("h23").levels, (Levels{{{-100, -80, -60, -40, -20, 0, 20, 40, 60, 80, 99},
                                           {-15, -10, -5, 0, 5, 10, 15},
                                           {-4, -2, 0, 2, 4}}}));
  EXPECT_EQ(Preset("h23").visits(), 23);
}

TEST(HierarchicalPresetTest, H21MatchesThesisTable45) {
  EXPECT_EQ(Preset("h21").levels, (Levels{{{-80, -60, -40, -20, 0, 20, 40, 60, 80},
                                           {-15, -10, -5, 0, 5, 10, 15},
                                           {-4, -2, 0, 2, 4}}}));
  EXPECT_EQ(Preset("h21").visits(), 21);
}

TEST(HierarchicalPresetTest, H19MatchesThesisTable45) {
  EXPECT_EQ(Preset("h19").levels, (Levels{{{-80, -60, -40, -20, 0, 20, 40, 60, 80},
                                           {-15, -10, -5, 0, 5, 10, 15},
                                           {-4, -2, 2}}}));
  EXPECT_EQ(Preset("h19").visits(), 19);
}

TEST(HierarchicalPresetTest, H17MatchesThesisTable45) {
  EXPECT_EQ(Preset("h17").levels,
            (Levels{{{-75, -50, -25, 0, 25, 50, 74}, {-15, -8, -1, 6, 13}, {-7, -4, -1, 2, 5}}}));
  EXPECT_EQ(Preset("h17").visits(), 17);
}

TEST(HierarchicalPresetTest, H15MatchesThesisTable45WithItsOneSidedLevelTwo) {
  EXPECT_EQ(Preset("h15").levels,
            (Levels{{{-75, -45, -15, 15, 45, 74}, {-30, -20, -10, 0}, {-6, -3, 0, 3, 6}}}));
  EXPECT_EQ(Preset("h15").visits(), 15);
}

TEST(HierarchicalSearchTest, ScoresAtMostItsVisitCountWithoutSubpixel) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 21, 6.0);
  const cv::Mat cur = testing::Translated(ref, 12, 0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  SearchOptions options;
  options.subpixel = false;
  for (const auto& preset : HierarchicalPresets()) {
    const SearchResult r = HierarchicalSearch(preset).Search(patch, cur, options);
    ASSERT_TRUE(r.found);
    EXPECT_LE(r.evaluations, preset.visits()) << preset.name;
    // Repeated positions are scored once: a level's centre, or h15's level 2 landing on level
    // 1's offsets, is not paid for twice.
    EXPECT_GE(r.evaluations, preset.visits() - 3) << preset.name;
    EXPECT_EQ(r.pixels_compared, static_cast<std::int64_t>(r.evaluations) * 10000);
  }
}

TEST(HierarchicalSearchTest, H23WithoutRefinementLandsOnEvenOffsetsOnly) {
  // Level 3 steps by 2, so the thesis's h23 is off by one pixel on odd shifts.
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 22, 8.0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  SearchOptions options;
  options.subpixel = false;
  const SearchResult r =
      HierarchicalSearch(Preset("h23")).Search(patch, testing::Translated(ref, 31, 0), options);
  EXPECT_EQ(std::abs(r.shift.x - 31), 1);
}

TEST(HierarchicalSearchTest, H23WithRefinementFindsAShiftOnASmoothScene) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 22, 8.0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  const HierarchicalSearch h23(Preset("h23"));
  for (const int dx : {-63, -8, 0, 31, 77}) {
    const SearchResult r = h23.Search(patch, testing::Translated(ref, dx, 0), {});
    EXPECT_EQ(r.shift.x, dx);
  }
}

TEST(HierarchicalSearchTest, H15CannotReachLargePositiveShifts) {
  // Level 1 tops out at +74, level 2 only looks left (−30…0) and level 3 adds at most +6:
  // the thesis's one-sided table cannot report anything beyond +80.
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 23, 8.0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  SearchOptions thesis;
  thesis.subpixel = false;  // the refinement's hill-climb would walk part of the way on
  const SearchResult r =
      HierarchicalSearch(Preset("h15")).Search(patch, testing::Translated(ref, 90, 0), thesis);
  EXPECT_LE(r.shift.x, 80);
}

TEST(HierarchicalSearchTest, ScalesOffsetsForOtherRanges) {
  const cv::Mat ref = testing::SmoothTexture({200, 200}, 24, 6.0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(75, 75, 50, 50)}, {SamplingKind::kAll}));
  SearchOptions options;
  options.range = 50;
  const SearchResult r =
      HierarchicalSearch(Preset("h23")).Search(patch, testing::Translated(ref, -33, 0), options);
  EXPECT_EQ(r.shift.x, -33);
}

}  // namespace
}  // namespace kapfix
