#include "common/search/axis_probe.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// EvaluateRun must score exactly what Evaluate scores shift by shift, whichever path it takes
// (the sliding sweep for a dense 8-bit reference, the per-shift loop otherwise).
void ExpectRunEqualsOneByOne(const ReferencePatch& reference, const cv::Mat& current, bool along_x,
                             cv::Point centre) {
  AxisProbe run(reference, current, along_x, centre, 200);
  AxisProbe single(reference, current, along_x, centre, 200);
  const int c = along_x ? centre.x : centre.y;
  run.EvaluateRun(c - 150, c + 150);  // wider than the frame allows: clamped
  std::int64_t distance = 0;
  for (int s = c - 150; s <= c + 150; ++s) single.Evaluate(s, &distance);
  ASSERT_FALSE(single.scored().empty());
  EXPECT_EQ(run.scored(), single.scored()) << (along_x ? "x" : "y") << " through " << centre;
}

TEST(AxisProbeTest, EvaluateRunEqualsEvaluatingEachShift) {
  const cv::Mat ref = testing::SmoothTexture({300, 240}, 7);
  const cv::Mat cur = testing::Translated(ref, 13, -6);
  for (const SamplingOptions sampling :
       {SamplingOptions{SamplingKind::kAll}, SamplingOptions{SamplingKind::kRandom, 0.1, 3}}) {
    const ReferencePatch reference(ref, SampleSet({cv::Rect(100, 70, 100, 100)}, sampling));
    for (const bool along_x : {true, false}) {
      ExpectRunEqualsOneByOne(reference, cur, along_x, {0, 0});
      ExpectRunEqualsOneByOne(reference, cur, along_x, {11, -5});
    }
  }
}

TEST(AxisProbeTest, EvaluateRunKeepsWhatWasScoredBefore) {
  const cv::Mat ref = testing::SmoothTexture({300, 300}, 8);
  const ReferencePatch reference(ref,
                                 SampleSet({cv::Rect(100, 100, 100, 100)}, {SamplingKind::kAll}));
  AxisProbe probe(reference, ref, true, {0, 0}, 100);
  std::int64_t distance = 0;
  ASSERT_TRUE(probe.Evaluate(5, &distance));
  probe.EvaluateRun(-10, 10);
  EXPECT_EQ(probe.evaluations(), 21);
  EXPECT_EQ(probe.scored().at(5), distance);
  EXPECT_EQ(probe.scored().at(0), 0);  // identical frames
}

}  // namespace
}  // namespace kapfix
