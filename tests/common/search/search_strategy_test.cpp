#include "common/search/search_strategy.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "common/image/color_channel.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

std::unique_ptr<SearchStrategy> Make(const std::string& name) {
  std::string error;
  auto strategy = MakeSearchStrategy(name, &error);
  EXPECT_NE(strategy, nullptr) << error;
  return strategy;
}

TEST(SearchStrategyTest, FactoryKnowsEveryNameAndRefusesOthers) {
  for (const std::string& name : SearchStrategyNames()) EXPECT_EQ(Make(name)->name(), name);
  std::string error;
  EXPECT_EQ(MakeSearchStrategy("h99", &error), nullptr);
  EXPECT_NE(error.find("h99"), std::string::npos);
}

TEST(SearchStrategyTest, ExhaustiveScoresEveryShiftInTheHalfOpenRange) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 31);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  SearchOptions options;
  options.subpixel = false;
  const SearchResult r = Make("all")->Search(patch, ref, options);
  EXPECT_EQ(r.evaluations, 200);  // [−100, +100): the thesis's 2,000,000 pixel comparisons
  EXPECT_EQ(r.pixels_compared, 2'000'000);
}

TEST(SearchStrategyTest, EveryStrategyFindsModerateShiftsOnARealPhoto) {
  const cv::Mat photo = testing::LoadOpenCvPhoto("aero1.jpg");
  ASSERT_FALSE(photo.empty());
  const cv::Mat plane = ExtractChannel(photo, ColorChannel::kGreen);
  const cv::Mat ref = plane(cv::Rect(100, 100, 300, 300)).clone();
  for (const std::string& name : SearchStrategyNames()) {
    if (name == "h15" || name == "h17") continue;  // their tables skip shifts; tested apart
    const ReferencePatch patch(
        ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kRandom, 0.1, 1}));
    for (const int dx : {-45, -12, 0, 6, 58}) {
      // Content moves by dx when the window over the photo moves by −dx.
      const cv::Mat cur = plane(cv::Rect(100 - dx, 100, 300, 300)).clone();
      const SearchResult r = Make(name)->Search(patch, cur, {});
      ASSERT_TRUE(r.found);
      EXPECT_EQ(r.shift.x, dx) << name;
      EXPECT_NEAR(r.displacement.x, dx, 0.5) << name;
    }
  }
}

TEST(SearchStrategyTest, EveryStrategyFindsTheSameShiftWithRgbAsWithGreenOnARealPhoto) {
  // The per-channel SSD (--channel rgb) runs on the BGR frame itself, through other code than
  // the green plane's (three-channel offsets, pyr's block scorer).
  const cv::Mat photo = testing::LoadOpenCvPhoto("aero1.jpg");
  ASSERT_EQ(photo.type(), CV_8UC3);
  const cv::Rect window(100, 100, 300, 300);
  const SampleSet set({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kRandom, 0.1, 1});
  for (const std::string& name : SearchStrategyNames()) {
    for (const cv::Point d : {cv::Point(-45, 0), cv::Point(23, 0), cv::Point(58, 0)}) {
      std::vector<SearchResult> results;
      for (const ColorChannel channel : {ColorChannel::kGreen, ColorChannel::kRgb}) {
        const cv::Mat plane = ExtractChannel(photo, channel);
        const ReferencePatch patch(plane(window).clone(), set);
        results.push_back(Make(name)->Search(patch, plane(window - d).clone(), {}));
        ASSERT_TRUE(results.back().found) << name;
      }
      EXPECT_EQ(results[1].shift, results[0].shift) << name << " at " << d;
      if (name != "h15" && name != "h17") {  // their tables skip shifts; tested apart
        EXPECT_EQ(results[1].shift.x, d.x) << name;
      }
    }
  }
}

TEST(SearchStrategyTest, SearchAlongYFindsAVerticalShift) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 32, 6.0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  SearchOptions options;
  options.axis = SearchAxis::kY;
  for (const std::string name : {"all", "h23", "pyr"}) {
    const SearchResult r = Make(name)->Search(patch, testing::Translated(ref, 0, -27), options);
    EXPECT_EQ(r.shift, cv::Point(0, -27)) << name;
  }
}

TEST(SearchStrategyTest, SearchAlongBothAxesFindsADiagonalShift) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 33, 8.0);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  SearchOptions options;
  options.axis = SearchAxis::kBoth;
  for (const std::string name : {"all", "pyr"}) {
    // Separable search: the X pass runs at y = 0, so the Y offset must stay small enough for
    // the X curve to keep its minimum (SPEC §2.3 "document the cost").
    const SearchResult r = Make(name)->Search(patch, testing::Translated(ref, 21, 3), options);
    EXPECT_EQ(r.shift, cv::Point(21, 3)) << name;
  }
}

TEST(SearchStrategyTest, SubpixelRecoversAFractionalShift) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 34, 5.0);
  cv::Mat cur;
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, 10.3, 0, 1, 0);
  cv::warpAffine(ref, cur, m, ref.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  const SearchResult r = Make("all")->Search(patch, cur, {});
  EXPECT_EQ(r.shift.x, 10);
  EXPECT_NEAR(r.displacement.x, 10.3, 0.12);
}

TEST(SearchStrategyTest, ConfidenceIsHighOnATextureAndLowOnAFlatPatch) {
  const cv::Mat textured = testing::SmoothTexture({300, 300}, 35, 4.0);
  const cv::Mat flat(300, 300, CV_8UC1, cv::Scalar(128));
  const SampleSet set({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll});
  const SearchResult sharp =
      Make("all")->Search(ReferencePatch(textured, set), testing::Translated(textured, 5, 0), {});
  const SearchResult ambiguous = Make("all")->Search(ReferencePatch(flat, set), flat, {});
  EXPECT_GT(sharp.confidence, 0.5);
  EXPECT_LT(ambiguous.confidence, 0.05);
}

TEST(SearchStrategyTest, EachAxisSaysHowSurelyThePatchIsPlacedAlongIt) {
  // Vertical stripes: one textured row repeated down the image. Across them (X) the patch has
  // one place; along them (Y) every shift fits as well (the aperture problem).
  const cv::Mat texture = testing::SmoothTexture({300, 300}, 37, 4.0);
  cv::Mat stripes;
  cv::repeat(texture.row(150), 300, 1, stripes);
  const SampleSet set({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll});
  SearchOptions options;
  options.axis = SearchAxis::kBoth;
  options.range = 20;
  for (const std::string name : {"all", "h23", "pyr"}) {
    const SearchResult r = Make(name)->Search(ReferencePatch(stripes, set),
                                              testing::Translated(stripes, 6, 4), options);
    ASSERT_TRUE(r.found) << name;
    EXPECT_EQ(r.shift.x, 6) << name;
    EXPECT_GT(r.confidence_x, 0.3) << name;  // above the loop's trust threshold (0.2)
    EXPECT_LT(r.confidence_y, 0.05) << name;
    EXPECT_EQ(r.confidence, std::min(r.confidence_x, r.confidence_y)) << name;
    const SearchResult textured = Make(name)->Search(ReferencePatch(texture, set),
                                                     testing::Translated(texture, 6, 4), options);
    EXPECT_GT(textured.confidence_x, 0.5) << name;
    EXPECT_GT(textured.confidence_y, 0.5) << name;
  }
}

TEST(SearchStrategyTest, AnAxisNotSearchedIsSure) {
  const cv::Mat texture = testing::SmoothTexture({300, 300}, 38, 4.0);
  const SampleSet set({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll});
  for (const std::string name : {"all", "pyr"}) {
    const SearchResult r =
        Make(name)->Search(ReferencePatch(texture, set), testing::Translated(texture, 6, 0), {});
    EXPECT_EQ(r.confidence_y, 1.0) << name;
    EXPECT_EQ(r.confidence, r.confidence_x) << name;
  }
}

TEST(SearchStrategyTest, NothingFoundWhenThePatchCannotMove) {
  const cv::Mat ref = testing::SmoothTexture({100, 100}, 36);
  const ReferencePatch patch(ref, SampleSet({cv::Rect(0, 0, 100, 100)}, {SamplingKind::kAll}));
  const cv::Mat small(50, 50, CV_8UC1, cv::Scalar(0));
  EXPECT_FALSE(Make("h23")->Search(patch, small, {}).found);
  EXPECT_FALSE(Make("pyr")->Search(patch, small, {}).found);
}

TEST(SearchStrategyTest, OptionsRefuseAnOutOfRangeRange) {
  SearchOptions options;
  options.range = 0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("range"), std::string::npos);
}

}  // namespace
}  // namespace kapfix
