#include "common/sampling/sample_set.hpp"

#include <gtest/gtest.h>

namespace kapfix {
namespace {

TEST(SampleSetTest, AllSamplingBecomesOneSpanPerRow) {
  const SampleSet set({cv::Rect(10, 20, 30, 4)}, {SamplingKind::kAll});
  EXPECT_EQ(set.size(), 120);
  ASSERT_EQ(set.spans().size(), 4u);
  EXPECT_TRUE(set.singles().empty());
  EXPECT_EQ(set.spans()[1].y, 21);
  EXPECT_EQ(set.spans()[1].x, 10);
  EXPECT_EQ(set.spans()[1].length, 30);
  EXPECT_EQ(set.bounds(), cv::Rect(10, 20, 30, 4));
}

TEST(SampleSetTest, ShortRunsStaySinglePoints) {
  const SampleSet set(std::vector<cv::Point>{{0, 0}, {1, 0}, {5, 0}, {5, 3}});
  EXPECT_TRUE(set.spans().empty());
  EXPECT_EQ(set.singles().size(), 4u);
}

TEST(SampleSetTest, OverlappingPatchesCountAPixelOnce) {
  const SampleSet set({cv::Rect(0, 0, 10, 10), cv::Rect(5, 0, 10, 10)}, {SamplingKind::kAll});
  EXPECT_EQ(set.size(), 150);
}

TEST(SampleSetTest, PointsListsSpansThenSingles) {
  std::vector<cv::Point> points;
  for (int x = 0; x < 9; ++x) points.emplace_back(x, 2);
  points.emplace_back(20, 0);
  const SampleSet set(points);
  const auto listed = set.Points();
  ASSERT_EQ(listed.size(), 10u);
  EXPECT_EQ(listed.front(), cv::Point(0, 2));
  EXPECT_EQ(listed.back(), cv::Point(20, 0));
}

}  // namespace
}  // namespace kapfix
