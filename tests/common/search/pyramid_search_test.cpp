#include "common/search/pyramid_search.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/image/color_channel.hpp"
#include "common/search/exhaustive_search.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// A 300×300 window of aero1.jpg's green plane whose content is moved by (dx, dy).
cv::Mat AeroWindow(int dx, int dy, double gain = 1.0) {
  static const cv::Mat plane =
      ExtractChannel(testing::LoadOpenCvPhoto("aero1.jpg"), ColorChannel::kGreen);
  cv::Mat window = plane(cv::Rect(150 - dx, 90 - dy, 300, 300)).clone();
  if (gain != 1.0) window.convertTo(window, CV_8U, gain);
  return window;
}

const SampleSet& CentralRandomTenth() {
  static const SampleSet set({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kRandom, 0.1, 1});
  return set;
}

TEST(PyramidSearchTest, ToleratesCrossAxisWobbleThatDefeatsAnXOnlySearch) {
  // The kite's view wobbles in Y while it swings in X: a 3-px Y offset on fine aerial texture.
  const ReferencePatch reference(AeroWindow(0, 0), CentralRandomTenth());
  const cv::Mat current = AeroWindow(-41, 3);
  const SearchResult pyr = PyramidSearch().Search(reference, current, {});
  ASSERT_TRUE(pyr.found);
  EXPECT_NEAR(pyr.displacement.x, -41, 1.0);
  EXPECT_EQ(pyr.shift.y, 3);  // the cross offset is found, not just tolerated
  const SearchResult all = ExhaustiveSearch().Search(reference, current, {});
  EXPECT_GT(std::abs(all.shift.x + 41), 2) << "X-only search unexpectedly robust here";
}

TEST(PyramidSearchTest, NoCrossRangeMeansAStrictlyOneAxisSearch) {
  const ReferencePatch reference(AeroWindow(0, 0), CentralRandomTenth());
  SearchOptions options;
  options.cross_range = 0;
  const SearchResult r = PyramidSearch().Search(reference, AeroWindow(23, 3), options);
  EXPECT_EQ(r.shift.y, 0);
}

TEST(PyramidSearchTest, HoldsItsMinimumUnderABrightnessDrift) {
  const ReferencePatch reference(AeroWindow(0, 0), CentralRandomTenth());
  const SearchResult r = PyramidSearch().Search(reference, AeroWindow(64, 0, 1.08), {});
  EXPECT_NEAR(r.displacement.x, 64, 1.0);
}

TEST(PyramidSearchTest, AnAnswerTheFinerLevelsWalkedOffTheCoarseOneIsNotTrusted) {
  // fruits.jpg under an uncorrected exposure step of 1.6 ×: the band-passed coarse level
  // stands on the view (4, −4) at a confidence of 0.26, but the raw-brightness descent of the
  // finer levels walks to (16, −4). Such an answer must not pass the trust threshold (0.2).
  static const cv::Mat plane =
      ExtractChannel(testing::LoadOpenCvPhoto("fruits.jpg"), ColorChannel::kGreen);
  const auto window = [](int dx, int dy) {
    return plane(cv::Rect(140 - dx, 60 - dy, 300, 300)).clone();
  };
  const ReferencePatch reference(window(0, 0), CentralRandomTenth());
  cv::Mat brighter;
  window(5, -3).convertTo(brighter, CV_8U, 1.6);
  SearchOptions options;
  options.axis = SearchAxis::kBoth;
  const SearchResult r = PyramidSearch().Search(reference, brighter, options);
  ASSERT_TRUE(r.found);
  ASSERT_GT(std::hypot(r.displacement.x - 5, r.displacement.y + 3), 4.0)
      << "the walk this test is about did not happen";
  EXPECT_EQ(r.confidence, 0.0);
  // The same view at the reference's brightness is matched and trusted.
  const SearchResult same = PyramidSearch().Search(reference, window(5, -3), options);
  EXPECT_NEAR(same.displacement.x, 5, 0.5);
  EXPECT_NEAR(same.displacement.y, -3, 0.5);
  EXPECT_GT(same.confidence, 0.2);
}

// A patch on the frame's bottom edge, as a bottom slice's is (text_motion.jpg, a 300×300
// window): its content moved down by 12 px has left the frame, and the lowest shift scored lies
// on the edge, the profile still falling towards it. That read 0 px at confidence 0.6-0.7 and
// was claimed in flight (boat, slice 9, 14-47 px off); it is no measurement on that axis. The
// same patch moved up is measured and trusted.
TEST(PyramidSearchTest, AMinimumOnTheFramesEdgeIsNotTrustedAlongThatAxis) {
  static const cv::Mat plane =
      ExtractChannel(testing::LoadOpenCvPhoto("text_motion.jpg"), ColorChannel::kGreen);
  const auto window = [](int dx, int dy) {
    return plane(cv::Rect(100 - dx, 40 - dy, 300, 300)).clone();
  };
  const SampleSet bottom({cv::Rect(100, 200, 100, 100)}, {SamplingKind::kRandom, 0.1, 1});
  const ReferencePatch reference(window(0, 0), bottom);
  SearchOptions options;
  options.axis = SearchAxis::kBoth;
  options.range = 40;
  const SearchResult down = PyramidSearch().Search(reference, window(2, 12), options);
  ASSERT_TRUE(down.found);
  ASSERT_LT(down.shift.y, 12) << "the shift this test is about is beyond the frame";
  EXPECT_EQ(down.confidence_y, 0.0) << "read " << down.shift.y << " px";
  EXPECT_EQ(down.confidence, 0.0);
  const SearchResult up = PyramidSearch().Search(reference, window(2, -12), options);
  EXPECT_NEAR(up.displacement.y, -12, 1.0);
  EXPECT_GT(up.confidence, 0.2);
}

TEST(PyramidSearchTest, BuildsTheReducedReferenceOncePerStoredReference) {
  const ReferencePatch reference(AeroWindow(0, 0), CentralRandomTenth());
  const PyramidSearch search;
  for (const int dx : {-12, 5, 30}) {
    ASSERT_TRUE(search.Search(reference, AeroWindow(dx, 0), {}).found);
  }
  // Copies of the stored reference share what was built for it.
  const ReferencePatch copy = reference;  // NOLINT(performance-unnecessary-copy-initialization)
  ASSERT_TRUE(search.Search(copy, AeroWindow(-7, 1), {}).found);
  EXPECT_EQ(search.reduced_references_built(), 1u);
  // Another stored reference gets its own.
  const ReferencePatch other(AeroWindow(9, 0), CentralRandomTenth());
  ASSERT_TRUE(search.Search(other, AeroWindow(0, 0), {}).found);
  ASSERT_TRUE(search.Search(other, AeroWindow(20, 0), {}).found);
  EXPECT_EQ(search.reduced_references_built(), 2u);
}

TEST(PyramidSearchTest, SixteenBitPlanesGiveTheSameAnswerAsEightBitOnes) {
  // The sum of three channels is a 16-bit plane, scored without the 8-bit kernels (SsdSlide,
  // SsdBlock): three equal channels make it 3 × the green plane, the same minimum.
  const auto sum_plane = [](const cv::Mat& green) {
    cv::Mat bgr;
    cv::merge(std::vector<cv::Mat>{green, green, green}, bgr);
    return ExtractChannel(bgr, ColorChannel::kRgbSum);
  };
  const cv::Mat ref8 = AeroWindow(0, 0);
  const cv::Mat cur8 = AeroWindow(-37, 2);
  const cv::Mat ref16 = sum_plane(ref8);
  ASSERT_EQ(ref16.type(), CV_16UC1);
  const SearchResult r8 =
      PyramidSearch().Search(ReferencePatch(ref8, CentralRandomTenth()), cur8, {});
  const SearchResult r16 =
      PyramidSearch().Search(ReferencePatch(ref16, CentralRandomTenth()), sum_plane(cur8), {});
  ASSERT_TRUE(r16.found);
  EXPECT_EQ(r16.shift, r8.shift);
  EXPECT_EQ(r16.shift, cv::Point(-37, 2));
}

TEST(PyramidSearchTest, ReportsLowConfidenceOnAFlatScene) {
  const cv::Mat flat(300, 300, CV_8UC1, cv::Scalar(90));
  const ReferencePatch reference(flat, CentralRandomTenth());
  const SearchResult r = PyramidSearch().Search(reference, flat, {});
  ASSERT_TRUE(r.found);
  EXPECT_LT(r.confidence, 0.05);
}

}  // namespace
}  // namespace kapfix
