#include "common/search/literal_hierarchical_search.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

const HierarchicalPreset& Preset(const std::string& name) {
  for (const auto& p : HierarchicalPresets()) {
    if (p.name == name) return p;
  }
  throw std::runtime_error("no preset " + name);
}

SearchOptions Literal() {
  SearchOptions options;
  options.subpixel = false;
  return options;
}

class LiteralHierarchicalSearchTest : public ::testing::Test {
 protected:
  const cv::Mat ref_ = testing::SmoothTexture({300, 300}, 22, 8.0);
  const ReferencePatch patch_{ref_,
                              SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll})};
};

// h19's level 3 (−4, −2, +2) leaves out its own centre: on a shift of exactly +40, level 1
// and level 2 land on it, but the thesis answers with level 3's best, 2 px away. The
// project's default keeps the lowest distance seen on any level and answers 40.
TEST_F(LiteralHierarchicalSearchTest, H19AnswersLevelThreeEvenWhenLevelTwoWasExact) {
  const cv::Mat cur = testing::Translated(ref_, 40, 0);
  const SearchResult literal =
      LiteralHierarchicalSearch(Preset("h19")).Search(patch_, cur, Literal());
  const SearchResult ours = HierarchicalSearch(Preset("h19")).Search(patch_, cur, Literal());
  EXPECT_EQ(std::abs(literal.shift.x - 40), 2);
  EXPECT_EQ(ours.shift.x, 40);
}

TEST_F(LiteralHierarchicalSearchTest, CountsEveryListedOffsetAsTheThesisNamesItsPresets) {
  const cv::Mat cur = testing::Translated(ref_, 12, 0);
  for (const auto& preset : HierarchicalPresets()) {
    const SearchResult r = LiteralHierarchicalSearch(preset).Search(patch_, cur, Literal());
    EXPECT_EQ(r.evaluations, preset.visits()) << preset.name;
    EXPECT_EQ(r.pixels_compared, static_cast<std::int64_t>(preset.visits()) * 10000);
  }
}

TEST_F(LiteralHierarchicalSearchTest, IgnoresSubpixelAndAnswersWholePixels) {
  SearchOptions options;  // subpixel on: the literal search still answers an integer
  const SearchResult r = LiteralHierarchicalSearch(Preset("h23"))
                             .Search(patch_, testing::Translated(ref_, 31, 0), options);
  EXPECT_EQ(r.displacement.x, static_cast<double>(r.shift.x));
}

TEST_F(LiteralHierarchicalSearchTest, H15StopsShortOfPlusEighty) {
  const SearchResult r = LiteralHierarchicalSearch(Preset("h15"))
                             .Search(patch_, testing::Translated(ref_, 90, 0), Literal());
  EXPECT_LE(r.shift.x, 80);
}

TEST(MakeLiteralSearchStrategyTest, RefusesPyrWithTheReason) {
  std::string error;
  EXPECT_EQ(MakeLiteralSearchStrategy("pyr", Literal(), &error), nullptr);
  EXPECT_NE(error.find("not the thesis"), std::string::npos) << error;
}

TEST(MakeLiteralSearchStrategyTest, RefusesSubpixel) {
  std::string error;
  EXPECT_EQ(MakeLiteralSearchStrategy("h23", SearchOptions{}, &error), nullptr);
  EXPECT_NE(error.find("sub-pixel"), std::string::npos) << error;
}

TEST(MakeLiteralSearchStrategyTest, RefusesBothAxes) {
  SearchOptions options = Literal();
  options.axis = SearchAxis::kBoth;
  std::string error;
  EXPECT_EQ(MakeLiteralSearchStrategy("h23", options, &error), nullptr);
}

TEST(MakeLiteralSearchStrategyTest, GivesThePresetsAndAll) {
  std::string error;
  for (const char* name : {"all", "h23", "h21", "h19", "h17", "h15"}) {
    const auto s = MakeLiteralSearchStrategy(name, Literal(), &error);
    ASSERT_NE(s, nullptr) << name << ": " << error;
    EXPECT_EQ(s->name(), name);
  }
}

}  // namespace
}  // namespace kapfix
