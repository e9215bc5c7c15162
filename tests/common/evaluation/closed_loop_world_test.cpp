// Each of the field's disturbances (issue 9) measurably degrades the closed loop against the
// nominal world with the same seed: the simulated world really does what its flag says.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "common/evaluation/closed_loop_evaluation.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr int kFrames = 300;

ClosedLoopFigures Fly(const WorldOptions& world, const std::string& controller = "predictive",
                      bool compensate_exposure = true) {
  ClosedLoopOptions options;
  options.frames = kFrames;
  options.world = world;
  options.controller = controller;
  options.fixation.compensate_exposure = compensate_exposure;
  return EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
}

const ClosedLoopFigures& Nominal(const std::string& controller, bool compensate_exposure) {
  static std::map<std::pair<std::string, bool>, ClosedLoopFigures> figures;
  const std::pair key{controller, compensate_exposure};
  if (!figures.contains(key)) {
    figures[key] = Fly(WorldOptions::Nominal(), controller, compensate_exposure);
  }
  return figures[key];
}

// The nominal world but for a servo latency of 1…`latency_jitter` frames, flown once per
// controller and jitter (several tests read the same flight).
const ClosedLoopFigures& UnderJitter(int latency_jitter, const std::string& controller) {
  static std::map<std::pair<int, std::string>, ClosedLoopFigures> figures;
  const std::pair key{latency_jitter, controller};
  if (!figures.contains(key)) {
    WorldOptions world;
    world.latency_jitter = latency_jitter;
    figures[key] = Fly(world, controller);
  }
  return figures[key];
}

struct Disturbance {
  std::string name;
  std::function<void(WorldOptions*)> turn_on;
  double min_ratio;  // the disturbed figure must be at least this × the nominal one
  // The figure that degrades: the view's RMS error for the platform's and the servos'
  // disturbances; the matcher's RMS miss for the image's (roll, blur, exposure), which the
  // loop's feedback then absorbs.
  double ClosedLoopFigures::*figure = &ClosedLoopFigures::rms_error_px;
  std::string controller = "predictive";
  // The loop's exposure compensation absorbs the exposure steps (ClosedLoopWrongLockTest):
  // what the world's flag does to the frames is measured on the raw matcher.
  bool compensate_exposure = true;
};

std::string DisturbanceName(const ::testing::TestParamInfo<Disturbance>& param) {
  return param.param.name;
}

class ClosedLoopWorldTest : public ::testing::TestWithParam<Disturbance> {};

TEST_P(ClosedLoopWorldTest, DegradesTheLoopAgainstTheNominalWorld) {
  WorldOptions world;
  GetParam().turn_on(&world);
  const ClosedLoopFigures disturbed =
      Fly(world, GetParam().controller, GetParam().compensate_exposure);
  const ClosedLoopFigures& nominal = Nominal(GetParam().controller, GetParam().compensate_exposure);
  const auto figure = GetParam().figure;
  EXPECT_GT(disturbed.*figure, GetParam().min_ratio * (nominal.*figure))
      << GetParam().name << ": " << disturbed.*figure << " px against nominal " << nominal.*figure
      << " px";
}

// Motion blur is not among them: it grows with the view's speed, which a working loop keeps
// to a few px per frame, and a symmetric smear barely moves the SSD minimum — measured on
// aero1 at 300 frames, +1 % confidence loss under P, +3 % matcher miss. Its effect on the
// frames is tested in scene_camera_test (MotionBlurGrowsWithTheViewsSpeed).
INSTANTIATE_TEST_SUITE_P(
    EachDisturbanceAlone, ClosedLoopWorldTest,
    ::testing::Values(
        Disturbance{"PeriodDrift", [](WorldOptions* w) { w->period_drift = 0.3; }, 1.1},
        Disturbance{"Sway", [](WorldOptions* w) { w->sway = true; }, 1.05},
        Disturbance{"Roll", [](WorldOptions* w) { w->roll_deg = 5; }, 1.1,
                    &ClosedLoopFigures::measurement_rms_px},
        Disturbance{"ExposureSteps", [](WorldOptions* w) { w->exposure_steps = true; }, 1.05,
                    &ClosedLoopFigures::measurement_rms_px, "predictive",
                    /*compensate_exposure=*/false},
        Disturbance{"LatencyJitter", [](WorldOptions* w) { w->latency_jitter = 4; }, 1.2},
        Disturbance{"FrameDrops", [](WorldOptions* w) { w->frame_drops = 0.1; }, 1.1},
        Disturbance{"CalibrationError", [](WorldOptions* w) { w->calibration_error = 1.6; }, 1.1}),
    DisturbanceName);

// Broadband wind replaces the nominal world's same-period gusts, so its baseline is a calm
// day (gusts off). As a force on the pendulum its response lives mostly at the swing's
// frequency, which the swing model forecasts: within SPEC §3's 100 px swing it barely shows
// (aero1, 300 frames, predictive: 3.28 px against 3.40 with the periodic gusts and 3.26 calm;
// P's error is the swing's and moves either way with the wind's random phase). So the test
// takes the swing away: on a rig at rest, wind is what the loop must hold against.
TEST(ClosedLoopWorldTest, BroadbandWindDegradesTheLoopOnARigAtRest) {
  const auto fly = [](WorldOptions::Gusts gusts) {
    ClosedLoopOptions options;
    options.frames = kFrames;
    options.platform.kite.amplitude_px = 0;
    options.world.gusts = gusts;
    return EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
  };
  const ClosedLoopFigures calm = fly(WorldOptions::Gusts::kOff);
  const ClosedLoopFigures wind = fly(WorldOptions::Gusts::kBroadband);
  EXPECT_GT(wind.rms_error_x_px, 1.2 * calm.rms_error_x_px)
      << "wind " << wind.rms_error_x_px << " px in x against calm " << calm.rms_error_x_px;
}

TEST(ClosedLoopWorldOptionsTest, RefusesAWorldOutOfRangeWithItsFlagInTheReason) {
  ClosedLoopOptions options;
  options.world.frame_drops = 0.9;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("--frame-drops"), std::string::npos) << error;
}

TEST(ClosedLoopWorldOptionsTest, TheSameSeedFliesTheSameRealisticWorld) {
  ClosedLoopOptions options;
  options.frames = 60;
  options.world = WorldOptions::Realistic();
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const ClosedLoopFigures a = EvaluateClosedLoop(scene, options);
  const ClosedLoopFigures b = EvaluateClosedLoop(scene, options);
  ASSERT_EQ(a.view_offsets.size(), b.view_offsets.size());
  for (std::size_t i = 0; i < a.view_offsets.size(); ++i) {
    EXPECT_EQ(a.view_offsets[i], b.view_offsets[i]) << "frame " << i;
  }
}

// Latency jitter of 1…2 frames: the loop resolves which command each frame was seen through
// (ServoBelief) and aims at every delay a command may take, so the predictive loop keeps
// most of its lead over P. Acting on the mean of the possible commands it was worse than P
// (aero1, 300 frames: 26.3 px against 23.6 at gain 1).
TEST(ClosedLoopJitterTest, ThePredictiveLoopStaysWellBelowPUnderLatencyJitter) {
  const ClosedLoopFigures& predictive = UnderJitter(2, "predictive");
  const ClosedLoopFigures& p = UnderJitter(2, "p");
  EXPECT_LT(predictive.rms_error_px, 0.5 * p.rms_error_px)
      << "predictive " << predictive.rms_error_px << " px, P " << p.rms_error_px << " px";
}

// Beyond the realistic preset's 1…2 frames: with commands taking 1…3 frames the loop still
// follows the swing well below P, and says so of every frame it misses grossly (aero1, 300
// frames: 10.5 px against P's 26.9, aim floor 6.7, 31 % gross, 0 silent). A loop that does not
// allow for the jitter (one delay assumed) left 20.8 px.
TEST(ClosedLoopJitterTest, ThePredictiveLoopStaysBelowPWhenACommandTakesOneToThreeFrames) {
  const ClosedLoopFigures& predictive = UnderJitter(3, "predictive");
  const ClosedLoopFigures& p = UnderJitter(3, "p");
  EXPECT_LT(predictive.rms_error_px, 0.6 * p.rms_error_px)
      << "predictive " << predictive.rms_error_px << " px, P " << p.rms_error_px << " px";
  EXPECT_LE(predictive.silent_gross_pct, 0.5) << "gross " << predictive.gross_pct << " %";
}

// The aim floor is what no aim removes: none at a fixed latency, and under jitter some, but
// never more than the loop itself leaves.
TEST(ClosedLoopJitterTest, TheAimFloorIsNoneAtAFixedLatencyAndBelowTheLoopUnderJitter) {
  EXPECT_EQ(Nominal("predictive", true).aim_floor_rms_px, 0.0);
  const ClosedLoopFigures& jitter = UnderJitter(2, "predictive");
  EXPECT_GT(jitter.aim_floor_rms_px, 0.5);
  EXPECT_LT(jitter.aim_floor_rms_px, jitter.rms_error_px);
  EXPECT_EQ(jitter.open_offsets.size(), jitter.view_offsets.size());
}

// The realistic world's pair: latency 1…2 frames with a lens calibration ×1.3 off. The servo
// belief reconstructed its views with the calibration and picked the wrong command of two, so
// the lock-on rang and the flight was far worse than with an exact calibration; it now finds
// the calibration's scale from the frames (ServoBelief::scale) and holds nearly as well.
TEST(ClosedLoopJitterTest, ACalibrationOffCostsLittleMoreThanTheJitterAlone) {
  WorldOptions off;
  off.latency_jitter = 2;
  off.calibration_error = 1.3;
  const ClosedLoopFigures& with_exact = UnderJitter(2, "predictive");
  const ClosedLoopFigures with_off = Fly(off);
  EXPECT_LT(with_off.rms_error_px, 1.3 * with_exact.rms_error_px)
      << "calibration ×1.3 " << with_off.rms_error_px << " px, exact " << with_exact.rms_error_px
      << " px";
}

// The realistic world's fastest lock-on (seed 3: the view moves up to 12 px a frame): the
// servo belief stays on the angle the servo showed. Deciding each frame alone, it drifted off
// through runs of late commands (views blended between two candidates carried their error
// into the next frame's extrapolation); it keeps hypotheses until a frame tells them apart.
TEST(ClosedLoopJitterTest, TheServoBeliefStaysOnTheServoThroughARealisticLockOn) {
  ClosedLoopOptions options;
  options.frames = 150;
  options.world = WorldOptions::Realistic();
  options.platform.kite.seed = options.platform.camera.seed = 3;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
  ASSERT_EQ(f.believed.size(), f.angles.size());
  double miss_sq = 0;
  int counted = 0;
  for (std::size_t k = 40; k < f.angles.size(); ++k) {
    if (!std::isfinite(f.believed[k].pan_deg)) continue;
    miss_sq += std::pow(f.believed[k].pan_deg - f.angles[k].pan_deg, 2);
    ++counted;
  }
  ASSERT_GT(counted, 80);
  const double miss_px = std::sqrt(miss_sq / counted) * options.platform.px_per_deg;
  EXPECT_LT(miss_px, 1.5) << "the belief's RMS miss of the pan servo " << miss_px << " px";
}

// A frame the camera drops is not seen, so the loop claims nothing for it: it counts in
// gross but never as silent (as in the agent's flight report, which has no record of it).
// Counted under the previous frame's claim, 3 dropped frames in 500 made board.jpg's realistic
// flight 0.6 % silent.
TEST(ClosedLoopDropsTest, ADroppedFrameIsNeverASilentGrossFrame) {
  ClosedLoopOptions options;
  options.frames = kFrames;
  options.world.frame_drops = 0.3;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
  int gross_dropped = 0, silent_seen = 0;
  for (std::size_t i = 0; i < f.view_offsets.size(); ++i) {
    const bool gross = std::hypot(f.view_offsets[i].x, f.view_offsets[i].y) > 10.0;
    const bool dropped = std::isnan(f.commanded[i].pan_deg);
    gross_dropped += gross && dropped ? 1 : 0;
    silent_seen += gross && !dropped && !f.off_target[i] ? 1 : 0;
  }
  ASSERT_GT(gross_dropped, 0) << "no dropped frame was grossly off: the test shows nothing";
  const double frames = static_cast<double>(f.view_offsets.size());
  EXPECT_DOUBLE_EQ(f.silent_gross_pct, 100.0 * silent_seen / frames)
      << gross_dropped << " gross dropped frames";
}

TEST(ClosedLoopAmbiguityTest, TheChessboardIsReportedNotSilentlyHeld) {
  // left01.jpg: a chessboard, whose neighbouring squares match nearly as well as the right
  // one. The loop may lose it, but must say so: nearly every frame whose true view error is
  // gross carries lock_lost. The operator's middle slice, whose patch is all squares.
  ClosedLoopOptions options;
  options.frames = 200;
  options.keep_slice = true;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("left01.jpg"), options);
  EXPECT_GT(f.lock_lost_pct, 50.0);
  EXPECT_LT(f.silent_gross_pct, 3.0) << "gross " << f.gross_pct << " %";
}

TEST(ClosedLoopAmbiguityTest, TheAgentHoldsTheChessboardsViewByASlicesPatchFoundSurely) {
  // The agent's slice: the middle patch, all squares, is ambiguous in the reference itself, so
  // the view is held by the nearest slice whose patch is not, without a silent frame. (Over
  // 500 frames the benchmark's seeds lose that patch too, and say so.)
  ClosedLoopOptions options;
  options.frames = 200;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("left01.jpg"), options);
  EXPECT_NE(f.slice, 5);
  EXPECT_LT(f.rms_error_px, 5.0) << "slice " << f.slice;
  EXPECT_LE(f.silent_gross_pct, 0.5) << "gross " << f.gross_pct << " %";
}

// building.jpg, rows of identical windows: before the lock needed confirming, 5.6 % of a
// nominal flight's frames were grossly off while the loop claimed its lock (500 frames, seed 1).
TEST(ClosedLoopAmbiguityTest, ARepetitiveFacadeIsReportedNotSilentlyHeld) {
  ClosedLoopOptions options;
  options.frames = 300;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("building.jpg"), options);
  EXPECT_GT(f.gross_pct, 10.0) << "the scene is meant to be lost";
  EXPECT_LE(f.silent_gross_pct, 0.5) << "gross " << f.gross_pct << " %";
}

// After SSP (issue 9: it counts as well as fixating from the first frame): the loop fixates the
// slice SSP recommends from the frame after the free swing, and holds a clean photo's view.
TEST(ClosedLoopStartTest, AfterSspTheLoopHoldsTheViewOfTheRecommendedSlice) {
  ClosedLoopOptions options;
  options.frames = 200;
  options.start = ClosedLoopOptions::Start::kAfterSsp;
  options.ssp_frames = 120;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
  EXPECT_GE(f.slice, 1);
  EXPECT_LE(f.slice, options.fixation.slice_count);
  EXPECT_LT(f.rms_error_px, 5.0);
  EXPECT_EQ(f.lock_lost_pct, 0.0);
}

// home.jpg in the realistic world, seed 3: SSP recommends slice 5, whose patch in the frame that
// becomes the reference is one the search finds in that very frame at confidence 0.19. Its
// matches were right, but the lock was never confirmed and the servos held: 100 % of frames
// lost, 50.9 px RMS. SSP's next slice whose patch passes is fixated instead.
TEST(ClosedLoopStartTest, AfterSspASliceWhosePatchIsWeakInTheReferenceFrameIsPassedOver) {
  ClosedLoopOptions options;
  options.frames = 150;
  options.start = ClosedLoopOptions::Start::kAfterSsp;
  options.world = WorldOptions::Realistic();
  options.platform.kite.seed = 3;
  options.platform.camera.seed = 3;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("home.jpg"), options);
  EXPECT_LT(f.lock_lost_pct, 20.0) << "slice " << f.slice;
  EXPECT_LT(f.rms_error_px, 15.0) << "slice " << f.slice;
}

// The realistic world's silent wrong lock after SSP (issue 9), aero1.jpg seed 1, slice 4: the
// reference is stored after the free swing at an exposure of 0.79 and from frame 200 on the
// frames are 1.6 × brighter. Uncompensated, pyr's raw-brightness finer levels walked 10–12 px
// off the view while its band-passed coarse level stood on it, and the loop claimed the view
// (14 % of 500 frames 10–20 px off, matcher miss 6.6 px RMS).
ClosedLoopFigures FlyRealisticAfterSsp(bool compensate_exposure) {
  ClosedLoopOptions options;
  options.frames = 320;  // past the exposure step at frame 200
  options.start = ClosedLoopOptions::Start::kAfterSsp;
  options.world = WorldOptions::Realistic();
  options.fixation.compensate_exposure = compensate_exposure;
  return EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
}

TEST(ClosedLoopWrongLockTest, AnExposureStepAfterSspIsCompensatedAndTheViewMeasuredRight) {
  const ClosedLoopFigures f = FlyRealisticAfterSsp(/*compensate_exposure=*/true);
  EXPECT_LT(f.measurement_rms_px, 2.0);
  EXPECT_LE(f.silent_gross_pct, 0.5) << "gross " << f.gross_pct << " %";
}

// Without the compensation the wrong matches remain, but pyr no longer trusts an answer its
// finer levels walked off the coarse one: the loop says it is off target instead of holding.
TEST(ClosedLoopWrongLockTest, UncompensatedTheWrongMatchesAreSaidNotHeld) {
  const ClosedLoopFigures f = FlyRealisticAfterSsp(/*compensate_exposure=*/false);
  EXPECT_GT(f.measurement_rms_px, 3.0) << "the wrong matches this test is about did not happen";
  EXPECT_LE(f.silent_gross_pct, 0.5) << "gross " << f.gross_pct << " %";
}

// Where the truth is taken (issue 9): the view error is the frame centre's, the loop fixates
// its slice. Under roll slice 3's patch (67 px above the centre) moves by about roll × 67 px
// against the centre, which a pan/tilt match cannot tell from a shift: measured against the
// centre the matcher seems to miss (aero1, roll ±5°: 1.65 px RMS), against the slice it does
// not (0.29 px). (Slices 1 and 2 share the patch at the frame's top edge, which this loop
// loses on aero1 with or without roll, and says so: lock lost on 64 % of the frames.)
TEST(ClosedLoopWorldTest, UnderRollAnOffCentreSliceIsMeasuredWhereTheLoopFixatesIt) {
  ClosedLoopOptions options;
  options.frames = kFrames;
  options.world.roll_deg = 5;
  options.fixation.slice = 3;
  const ClosedLoopFigures f = EvaluateClosedLoop(testing::LoadOpenCvPhoto("aero1.jpg"), options);
  EXPECT_LT(f.slice_miss_rms_px, 0.5);
  EXPECT_GT(f.measurement_rms_px, 3 * f.slice_miss_rms_px)
      << "against the centre " << f.measurement_rms_px << " px, the slice " << f.slice_miss_rms_px
      << " px";
}

// A moving start fixates one frame into the swing (its reference carries the swing's blur):
// the view it holds is frame 1's, and its flight the first-frame start's, one frame on.
TEST(ClosedLoopStartTest, AMovingStartTakesItsReferenceOneFrameIntoTheSwing) {
  ClosedLoopOptions options;
  options.frames = 20;
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const ClosedLoopFigures first = EvaluateClosedLoop(scene, options);
  options.start = ClosedLoopOptions::Start::kMoving;
  const ClosedLoopFigures moving = EvaluateClosedLoop(scene, options);
  ASSERT_EQ(moving.open_offsets.size(), first.open_offsets.size());
  // The swing moved between frames 1 and 2: the shift is seen.
  ASSERT_GT(cv::norm(first.open_offsets[1] - first.open_offsets[0]), 1.0);
  for (std::size_t k = 0; k + 1 < first.open_offsets.size(); ++k) {
    EXPECT_NEAR(moving.open_offsets[k].x, first.open_offsets[k + 1].x, 1e-9) << k;
    EXPECT_NEAR(moving.open_offsets[k].y, first.open_offsets[k + 1].y, 1e-9) << k;
  }
}

TEST(ClosedLoopStartTest, RefusesAFreeSwingOfFewerThanTwoFrames) {
  ClosedLoopOptions options;
  options.start = ClosedLoopOptions::Start::kAfterSsp;
  options.ssp_frames = 1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("SSP"), std::string::npos) << error;
}

// Blender_Suzanne1.jpg's centre is a smooth face the swing's blur wipes out: fixated there from
// the first frame (realistic world, seed 3), the operator's pick, the lock is lost within 5
// frames and the wide search never finds it again. SSP over the swing the held servos leave
// free names a slice whose patch the swing does not lose, and the same reference is held by it.
ClosedLoopFigures FlySuzanneFromTheFirstFrame(int ssp_after_lost_frames, bool keep_slice = true) {
  ClosedLoopOptions options;
  options.keep_slice = keep_slice;
  options.frames = 420;
  options.world = WorldOptions::Realistic();
  options.platform.kite.seed = 3;
  options.platform.camera.seed = 3;
  options.ssp_frames = 150;
  options.ssp_after_lost_frames = ssp_after_lost_frames;
  return EvaluateClosedLoop(testing::LoadOpenCvPhoto("Blender_Suzanne1.jpg"), options);
}

// [px] RMS view error, and the share of frames with the lock lost [%], over the last `frames`.
std::pair<double, double> LastFrames(const ClosedLoopFigures& f, std::size_t frames) {
  double sum = 0;
  int lost = 0;
  for (std::size_t k = f.view_offsets.size() - frames; k < f.view_offsets.size(); ++k) {
    sum += f.view_offsets[k].dot(f.view_offsets[k]);
    lost += f.lock_lost[k] ? 1 : 0;
  }
  return {std::sqrt(sum / static_cast<double>(frames)), 100.0 * lost / static_cast<double>(frames)};
}

TEST(ClosedLoopLostLockTest, ALockThatStaysLostIsHeldAgainBySspsSliceOnTheSameReference) {
  const ClosedLoopFigures without = FlySuzanneFromTheFirstFrame(0);
  const ClosedLoopFigures with = FlySuzanneFromTheFirstFrame(60);
  const auto [rms_without, lost_without] = LastFrames(without, 150);
  const auto [rms_with, lost_with] = LastFrames(with, 150);
  EXPECT_EQ(without.slices_after_lost_lock, 0);
  EXPECT_GT(lost_without, 90.0) << "the premise: the centre's lock is lost and stays lost";
  EXPECT_GT(rms_without, 20.0);
  EXPECT_EQ(with.slices_after_lost_lock, 1);
  EXPECT_NE(with.slice, without.slice);
  EXPECT_LT(lost_with, 10.0) << "slice " << with.slice;
  EXPECT_LT(rms_with, 8.0) << "slice " << with.slice;
}

TEST(ClosedLoopLostLockTest, RefusesANegativeWait) {
  ClosedLoopOptions options;
  options.ssp_after_lost_frames = -1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("lost lock"), std::string::npos) << error;
}

// The same face, the agent's slice: the middle patch is weak in the reference (the search
// finds it in its own frame at 0.06), so the view is held by the nearest slice's patch found
// surely there, from the first frame on.
TEST(ClosedLoopWeakPatchTest, AWeakMiddlePatchGivesWayToTheNearestSureSliceFromTheFirstFrame) {
  const ClosedLoopFigures kept = FlySuzanneFromTheFirstFrame(0);
  const ClosedLoopFigures moved = FlySuzanneFromTheFirstFrame(0, /*keep_slice=*/false);
  EXPECT_EQ(kept.slice, 5);
  EXPECT_GT(kept.rms_error_px, 20.0) << "the premise: the middle patch's lock never comes";
  EXPECT_NE(moved.slice, 5);
  EXPECT_LE(std::abs(moved.slice - 5), 2) << "the nearest sure slice, not any";
  EXPECT_LT(moved.rms_error_px, 8.0) << "slice " << moved.slice;
  const auto [rms_late, lost_late] = LastFrames(moved, 150);
  EXPECT_LT(lost_late, 5.0);
  EXPECT_LT(rms_late, 8.0);
  EXPECT_LE(moved.silent_gross_pct, 0.5);
}

}  // namespace
}  // namespace kapfix
