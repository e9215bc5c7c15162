#include "common/evaluation/swing_evaluation.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// Frames whose content moves by known integer amounts along x.
struct KnownSwing {
  std::vector<cv::Mat> planes;
  std::vector<cv::Point2d> truth;
};

KnownSwing MakeKnownSwing(const std::vector<int>& shifts) {
  const cv::Mat scene = testing::SmoothTexture({300, 300}, 51, 6.0);
  KnownSwing swing;
  for (const int dx : shifts) {
    swing.planes.push_back(testing::Translated(scene, dx, 0));
    swing.truth.emplace_back(dx, 0);
  }
  return swing;
}

std::unique_ptr<SearchStrategy> Strategy(const std::string& name) {
  std::string error;
  return MakeSearchStrategy(name, &error);
}

TEST(SwingEvaluationTest, PerfectTrackingHasNoError) {
  const KnownSwing swing = MakeKnownSwing({0, 10, -20, 35, 5});
  SwingEvaluationOptions options;
  options.sampling = {SamplingKind::kAll};
  const SwingEvaluation e =
      EvaluateSwing(swing.planes, swing.truth, {100, 100, 100, 100}, *Strategy("all"), options);
  ASSERT_EQ(e.errors_px.size(), 4u);
  EXPECT_NEAR(e.mean_abs_err_px, 0.0, 0.05);
  EXPECT_DOUBLE_EQ(e.within_2px_pct, 100.0);
  EXPECT_DOUBLE_EQ(e.gross_fail_pct, 0.0);
  // The sub-pixel neighbours were already scored by the exhaustive pass: no extra work.
  EXPECT_DOUBLE_EQ(e.pixels_per_estimate, 2'000'000);
  EXPECT_EQ(e.search_us.size(), 4u);
}

TEST(SwingEvaluationTest, WrongTruthCountsAsGrossFailure) {
  KnownSwing swing = MakeKnownSwing({0, 10, 20});
  swing.truth[2].x = 50;  // the search will say 20: 30 px off
  SwingEvaluationOptions options;
  const SwingEvaluation e =
      EvaluateSwing(swing.planes, swing.truth, {100, 100, 100, 100}, *Strategy("all"), options);
  EXPECT_DOUBLE_EQ(e.gross_fail_pct, 50.0);
  EXPECT_DOUBLE_EQ(e.within_2px_pct, 50.0);
  EXPECT_NEAR(e.mean_abs_err_px, 15.0, 0.1);
}

TEST(SwingEvaluationTest, RefusesMismatchedTruth) {
  KnownSwing swing = MakeKnownSwing({0, 10});
  swing.truth.pop_back();
  EXPECT_THROW(EvaluateSwing(swing.planes, swing.truth, {100, 100, 100, 100}, *Strategy("all"), {}),
               std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
