// The agent's own loop (MakeClosedLoopOptions) in the realistic world, on photos the benchmark
// does not fly, where the lock used to be lost though every match was right.
#include <gtest/gtest.h>

#include <cstdint>

#include "agent/agent.hpp"
#include "agent/modes/run_options.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix::agent {
namespace {

// From the first frame, 500 frames, as `kapfix-bench-loop --scenes PHOTO` flies seed `seed`.
ClosedLoopFigures Fly(const char* photo, int seed, bool axis_trust = true,
                      bool roll_tracking = true) {
  AgentConfig config = BuiltInConfig(MotionKind::kKite);
  config.simulation.world = WorldOptions::Realistic();
  ClosedLoopOptions options = MakeClosedLoopOptions(config);
  options.frames = 500;
  options.platform.kite.seed = options.platform.boat.seed = options.platform.camera.seed =
      static_cast<std::uint32_t>(seed);
  options.fixation.axis_trust = axis_trust;
  options.fixation.roll_tracking.enabled = roll_tracking;
  return EvaluateClosedLoop(testing::LoadOpenCvPhoto(photo), options);
}

// With the reference upright whatever the roll (RollingReference off): the reference turned by
// the roll makes aloeL.jpg's Y matches surer too, and this seed then keeps its lock either way
// (session 25), which would leave the rule below untested.
ClosedLoopFigures FlyAloe(bool axis_trust) { return Fly("aloeL.jpg", 2, axis_trust, false); }

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

// stuff.jpg seed 3: on the lock-on's second frame the view moves 36 px a frame and its blur
// drops the confidence to 0.04, the match right. Lost at that first untrusted frame (the rule
// until session 23 for a lock not yet confirmed), the lock came back only at frame 14 with the
// view 113 px off: 14.8 px RMS, 2.4 % of the frames lost.
TEST(AgentLoopLockOnTest, ABlurredFrameOnTheLockOnIsRiddenOutNotALostLock) {
  const ClosedLoopFigures f = Fly("stuff.jpg", 3);
  EXPECT_EQ(f.lock_lost_pct, 0.0);
  EXPECT_LT(f.rms_error_px, 10.0);
  EXPECT_EQ(f.silent_gross_pct, 0.0);
}

}  // namespace
}  // namespace kapfix::agent
