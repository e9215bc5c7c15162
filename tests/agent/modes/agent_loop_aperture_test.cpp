// The agent's own loop (MakeClosedLoopOptions) over a photo whose patch is placed surely along
// one axis only: aloeL.jpg's aloe leaves, in the realistic world.
#include <gtest/gtest.h>

#include "agent/agent.hpp"
#include "agent/modes/run_options.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix::agent {
namespace {

// Seed 2 from the first frame, 500 frames, as `kapfix-bench-loop --scenes aloeL.jpg` flies it.
ClosedLoopFigures FlyAloe(bool axis_trust) {
  AgentConfig config = BuiltInConfig(MotionKind::kKite);
  config.simulation.world = WorldOptions::Realistic();
  ClosedLoopOptions options = MakeClosedLoopOptions(config);
  options.frames = 500;
  options.platform.kite.seed = options.platform.boat.seed = options.platform.camera.seed = 2;
  options.fixation.axis_trust = axis_trust;
  return EvaluateClosedLoop(testing::LoadOpenCvPhoto("aloeL.jpg"), options);
}

// Its frames are often sure along X and not along Y (confidence 0.3-0.7 against 0.05-0.3):
// counted untrusted, five of them between clear ones lost the lock for 29 frames (frames
// 142-170, the view up to 74 px off) though every match was right.
TEST(AgentLoopApertureTest, AStripedPhotosLockRidesOnTheAxisItsMatchesAreSureOf) {
  const ClosedLoopFigures steered = FlyAloe(/*axis_trust=*/true);
  EXPECT_EQ(steered.lock_lost_pct, 0.0);
  EXPECT_LT(steered.rms_error_px, 6.0);
  EXPECT_EQ(steered.silent_gross_pct, 0.0);
  const ClosedLoopFigures both_or_none = FlyAloe(/*axis_trust=*/false);
  EXPECT_GT(both_or_none.lock_lost_pct, 5.0) << "the loss this test is about did not happen";
  EXPECT_GT(both_or_none.rms_error_px, 2 * steered.rms_error_px);
}

}  // namespace
}  // namespace kapfix::agent
