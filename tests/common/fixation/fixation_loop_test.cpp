#include "common/fixation/fixation_loop.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "common/control/calibration.hpp"
#include "common/control/proportional_controller.hpp"
#include "common/selection/slice_geometry.hpp"
#include "common/sim/simulated_platform.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr LensCalibration kLens{0.1, 0.1};  // [deg/px]

std::shared_ptr<const SearchStrategy> Pyr() {
  std::string error;
  return MakeSearchStrategy("pyr", &error);
}

std::unique_ptr<Controller> PlainP() {
  ControllerGains gains;
  gains.dead_band_px = 0;
  return std::make_unique<ProportionalController>(gains, kLens);
}

FixationOptions Options(SearchAxis axis = SearchAxis::kBoth) {
  FixationOptions o;
  o.search.axis = axis;
  return o;
}

cv::Mat Texture() {
  cv::Mat grey = testing::SmoothTexture({300, 300}, 11, 3.0);
  cv::Mat bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

TEST(FixationLoopTest, CorrectsTheMeasuredDisplacementThroughTheCalibration) {
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  const FixationLoop::Step step =
      loop.Process(testing::Translated(reference, 7, -4), {1.0, 2.0}, 0.04);
  ASSERT_TRUE(step.match.found);
  EXPECT_NEAR(step.match.displacement.x, 7, 0.2);
  EXPECT_NEAR(step.match.displacement.y, -4, 0.2);
  EXPECT_NEAR(step.targets.pan_deg, 1.0 + 0.7, 0.02);
  EXPECT_NEAR(step.targets.tilt_deg, 2.0 - 0.4, 0.02);
  EXPECT_FALSE(step.lock_lost);
  EXPECT_GT(step.loop_us, 0.0);
}

TEST(FixationLoopTest, PatchSitsOnTheChosenSlice) {
  FixationOptions o = Options();
  o.slice = 3;
  o.patch_size = 60;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  loop.SetReference(Texture());
  EXPECT_EQ(loop.patch(), SlicePatch({300, 300}, 9, 3, 60));
}

TEST(FixationLoopTest, AxisNotSearchedIsNotControlled) {
  FixationLoop loop(Options(SearchAxis::kX), Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  const FixationLoop::Step step =
      loop.Process(testing::Translated(reference, 6, 3), {0.0, 5.0}, 0.04);
  EXPECT_NEAR(step.targets.pan_deg, 0.6, 0.02);
  EXPECT_DOUBLE_EQ(step.targets.tilt_deg, 5.0);
}

TEST(FixationLoopTest, WithoutAReferenceHoldsAndReportsTheLockLost) {
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  const FixationLoop::Step step = loop.Process(Texture(), {3.0, 4.0}, 0.04);
  EXPECT_TRUE(step.lock_lost);
  EXPECT_FALSE(step.match.found);
  EXPECT_DOUBLE_EQ(step.targets.pan_deg, 3.0);
  EXPECT_DOUBLE_EQ(step.targets.tilt_deg, 4.0);
}

// Frames of the reference view itself until the lock is confirmed (lock_regain_frames clear
// frames in a row).
void ConfirmLock(FixationLoop& loop, const cv::Mat& reference) {
  for (int k = 0; k < loop.options().lock_regain_frames; ++k) {
    ASSERT_FALSE(loop.Process(reference, {}, 0.04).lock_lost);
  }
}

TEST(FixationLoopTest, LockIsLostAfterTheConfiguredRunOfUntrustedFrames) {
  FixationOptions o = Options();
  o.lock_lost_frames = 3;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  ConfirmLock(loop, reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));  // matches everywhere equally
  EXPECT_FALSE(loop.Process(blank, {}, 0.04).lock_lost);
  EXPECT_FALSE(loop.Process(blank, {}, 0.04).lock_lost);
  const FixationLoop::Step third = loop.Process(blank, {1.0, 1.0}, 0.04);
  EXPECT_TRUE(third.lock_lost);
  // Lost: the servos head for the centre of the swing seen, the reference view at 0°.
  EXPECT_NEAR(third.targets.pan_deg, 0.0, 0.01);
}

// A lost lock sends the servos to the centre of the swing seen while the view was tracked,
// not holding them where the last (perhaps wrong) matches left them (baboon.jpg after SSP:
// parked 65 px off, 92 px RMS against the swing's own 38), nor back to where the reference
// was seen, which may be the swing's far end (left01.jpg after SSP: 48.6 px against 26.1
// about the swing's centre). The centre is the mean of the angles that centred the view: the
// reference's, then each trusted frame's angles plus its displacement in degrees.
TEST(FixationLoopTest, ALostLockSendsTheServosToTheCentreOfTheSwingSeen) {
  FixationOptions o = Options();
  o.lock_lost_frames = 2;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference, ServoTargets{-2.0, 3.0});
  // Seen 6 px right and 4 px up through (1, 1): centred at (1.6, 0.6), three times.
  for (int k = 0; k < o.lock_regain_frames; ++k) {
    ASSERT_TRUE(loop.Process(testing::Translated(reference, 6, -4), {1.0, 1.0}, 0.04).trusted);
  }
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  const FixationLoop::Step first = loop.Process(blank, {5.0, -1.0}, 0.04);
  ASSERT_FALSE(first.lock_lost);
  EXPECT_DOUBLE_EQ(first.targets.pan_deg, 5.0);  // a confirmed lock rides it out, holding
  const FixationLoop::Step lost = loop.Process(blank, {5.0, -1.0}, 0.04);
  ASSERT_TRUE(lost.lock_lost);
  EXPECT_NEAR(lost.targets.pan_deg, (-2.0 + 3 * 1.6) / 4, 0.015);
  EXPECT_NEAR(lost.targets.tilt_deg, (3.0 + 3 * 0.6) / 4, 0.015);
}

// The same view held by another patch after SSP (KeepSwingCentre): the previous patch's swing
// centre stands until the new lock is confirmed, and the new patch's unconfirmed frames, which
// on a chessboard may sit a square off, do not move it; once confirmed, the swing seen from
// then on takes over.
TEST(FixationLoopTest, AKeptSwingCentreStandsUntilTheLockIsConfirmed) {
  FixationOptions o = Options();
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference, ServoTargets{-2.0, 3.0});
  loop.KeepSwingCentre(ServoTargets{4.0, -1.0});
  // Seen 6 px right and 4 px up through (1, 1): centred at (1.6, 0.6).
  for (int k = 0; k < o.lock_regain_frames; ++k) {
    const std::optional<ServoTargets> before = loop.swing_centre();
    ASSERT_TRUE(before);
    EXPECT_DOUBLE_EQ(before->pan_deg, 4.0) << "frame " << k;
    EXPECT_DOUBLE_EQ(before->tilt_deg, -1.0) << "frame " << k;
    ASSERT_TRUE(loop.Process(testing::Translated(reference, 6, -4), {1.0, 1.0}, 0.04).trusted);
  }
  const std::optional<ServoTargets> after = loop.swing_centre();
  ASSERT_TRUE(after);
  EXPECT_NEAR(after->pan_deg, 1.6, 0.015);
  EXPECT_NEAR(after->tilt_deg, 0.6, 0.015);
}

// The centre forgets trusted frames older than swing_centre_frames (the line's slow sway
// moves it), the reference's own angles among them.
TEST(FixationLoopTest, TheSwingsCentreForgetsFramesBeyondItsWindow) {
  FixationOptions o = Options();
  o.swing_centre_frames = 2;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference, ServoTargets{-2.0, 3.0});
  ASSERT_TRUE(loop.Process(testing::Translated(reference, 6, 0), {1.0, 1.0}, 0.04).trusted);
  ASSERT_TRUE(loop.Process(testing::Translated(reference, -4, 0), {2.0, 1.0}, 0.04).trusted);
  ASSERT_TRUE(loop.Process(testing::Translated(reference, 2, 0), {1.0, 2.0}, 0.04).trusted);
  const std::optional<ServoTargets> centre = loop.swing_centre();
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->pan_deg, (1.6 + 1.2) / 2, 0.015);
  EXPECT_NEAR(centre->tilt_deg, (1.0 + 2.0) / 2, 0.015);
}

// A view taken up after a restart has no known angles: until a frame is trusted there is no
// swing seen, and a lost lock holds the servos where they are.
TEST(FixationLoopTest, ALostLockWithNoAnglesAndNoTrustedFrameHoldsTheServos) {
  FixationOptions o = Options();
  o.lock_lost_frames = 1;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  loop.SetReference(Texture());
  EXPECT_FALSE(loop.swing_centre());
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  const FixationLoop::Step lost = loop.Process(blank, {5.0, -1.0}, 0.04);
  ASSERT_TRUE(lost.lock_lost);
  EXPECT_DOUBLE_EQ(lost.targets.pan_deg, 5.0);
  EXPECT_DOUBLE_EQ(lost.targets.tilt_deg, -1.0);
}

// The centre is in the degrees the controller acts on: once it trusts its own estimate of
// the lens, that one, not the stored calibration.
TEST(FixationLoopTest, TheSwingsCentreUsesTheControllersTrustedEstimate) {
  // P that reports an estimate of its own.
  class EstimatingP : public Controller {
   public:
    ServoTargets Update(const ControlInput& input, const ServoTargets& current) override {
      return p_->Update(input, current);
    }
    void Reset() override { p_->Reset(); }
    std::string name() const override { return "estimating p"; }
    void SetCalibration(const LensCalibration& calibration) override {
      p_->SetCalibration(calibration);
    }
    void SetGains(const ControllerGains& gains) override { p_->SetGains(gains); }
    std::optional<ControlEstimate> estimate() const override {
      ControlEstimate e;
      e.pan = {0.2, 0.01, true, 0};
      e.tilt = {0.3, 1.0, false, 0};  // not trusted: the stored 0.1
      return e;
    }

   private:
    std::unique_ptr<Controller> p_ = PlainP();
  };
  FixationLoop loop(Options(), Pyr(), std::make_unique<EstimatingP>(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  ASSERT_TRUE(loop.Process(testing::Translated(reference, 5, 5), {1.0, 1.0}, 0.04).trusted);
  const std::optional<ServoTargets> centre = loop.swing_centre();
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->pan_deg, 1.0 + 5 * 0.2, 0.03);
  EXPECT_NEAR(centre->tilt_deg, 1.0 + 5 * 0.1, 0.03);
}

// A frame outside the flight (the one before the reference) is located against the
// reference, and neither the lock nor the controller hears of it.
TEST(FixationLoopTest, LocatesTheReferenceInAFrameWithoutSteering) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const cv::Rect window((scene.cols - 300) / 2, (scene.rows - 300) / 2, 300, 300);
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  loop.SetReference(scene(window).clone());
  // The view moved by (+9, −3) px from that frame to the reference: there the reference's
  // patch lies (−9, +3) px off (stored-reference convention).
  const std::optional<cv::Point2d> at = loop.Locate(scene(window + cv::Point(9, -3)).clone());
  ASSERT_TRUE(at.has_value());
  EXPECT_NEAR(at->x, -9, 0.3);
  EXPECT_NEAR(at->y, 3, 0.3);
  // The next frame is the flight's first: P corrects only its own displacement.
  const FixationLoop::Step step =
      loop.Process(testing::Translated(scene(window).clone(), 4, 0), {0, 0}, 0.04);
  EXPECT_NEAR(step.targets.pan_deg, 0.4, 0.03);
}

TEST(FixationLoopTest, AFrameThatDoesNotShowTheReferenceIsNotLocated) {
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  EXPECT_FALSE(loop.Locate(Texture()).has_value()) << "no reference yet";
  loop.SetReference(Texture());
  EXPECT_FALSE(loop.Locate(testing::SmoothTexture({300, 300}, 99, 3.0)).has_value());
}

// Re-acquired, the measurement steers again: the return ends with the loss.
TEST(FixationLoopTest, AReacquiredLockSteersByTheMatchNotBackToTheReferenceAngles) {
  FixationOptions o = Options();
  o.lock_lost_frames = 1;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference, ServoTargets{-2.0, 3.0});
  ConfirmLock(loop, reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  ASSERT_TRUE(loop.Process(blank, {5.0, -1.0}, 0.04).lock_lost);
  FixationLoop::Step step;
  for (int k = 0; k < o.lock_regain_frames; ++k) {
    step = loop.Process(testing::Translated(reference, 6, 0), {1.0, 1.0}, 0.04);
  }
  ASSERT_TRUE(step.trusted);
  EXPECT_NEAR(step.targets.pan_deg, 1.0 + 0.6, 0.02);
  EXPECT_NEAR(step.targets.tilt_deg, 1.0, 0.02);
}

TEST(FixationLoopTest, ARunOfClearFramesEndsARunOfUntrustedOnes) {
  FixationOptions o = Options();
  o.lock_lost_frames = 2;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  ConfirmLock(loop, reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  loop.Process(blank, {}, 0.04);
  ConfirmLock(loop, reference);
  EXPECT_FALSE(loop.Process(blank, {}, 0.04).lock_lost);
}

// A chessboard's slice may give a right match and an ambiguous one frame by frame: single good
// frames between the bad ones do not keep the lock.
TEST(FixationLoopTest, GoodFramesBetweenUntrustedOnesDoNotKeepTheLock) {
  FixationOptions o = Options();
  o.lock_lost_frames = 3;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  ConfirmLock(loop, reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  bool lost = false;
  for (int k = 0; k < 3; ++k) {
    lost = loop.Process(blank, {}, 0.04).lock_lost;
    if (k < 2) {
      EXPECT_FALSE(loop.Process(reference, {}, 0.04).lock_lost);
    }
  }
  EXPECT_TRUE(lost);
}

// A lock-on's first frames may be blurred by a fast swing (stuff.jpg, realistic world, seed
// 3: confidence 0.04 on frame 2 with the match right): a lock not yet confirmed rides them out
// like a confirmed one, claiming none of them, and is lost at the run's end.
TEST(FixationLoopTest, ALockNotYetConfirmedRidesOutUntrustedFramesClaimingNone) {
  FixationOptions o = Options();
  o.lock_lost_frames = 5;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  loop.SetReference(Texture());
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  for (int k = 1; k < o.lock_lost_frames; ++k) {
    const FixationLoop::Step step = loop.Process(blank, {}, 0.04);
    EXPECT_FALSE(step.lock_lost) << "untrusted frame " << k;
    EXPECT_FALSE(step.trusted);
    EXPECT_TRUE(step.off_target);
  }
  EXPECT_TRUE(loop.Process(blank, {}, 0.04).lock_lost);
}

// building.jpg: rows of identical windows, the silent wrong lock (5.6 % of a nominal
// flight's frames grossly off with lock_lost false). Its matches hover around the trust
// threshold (0.05-0.3), right or one window off: such a lock is never confirmed, so the loop
// claims none of its frames but the first, says the lock is lost once it has ridden out
// lock_lost_frames untrusted ones, and keeps saying so.
TEST(FixationLoopTest, ARepetitivePhotosLockIsReportedLostNotSilentlyHeld) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("building.jpg");
  const cv::Rect window((scene.cols - 300) / 2, (scene.rows - 300) / 2, 300, 300);
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  loop.SetReference(scene(window).clone());
  int lost = 0;
  int claimed = 0;
  int frames = 0;
  for (int dx = -40; dx <= 40; dx += 8) {
    const cv::Mat frame = scene(window + cv::Point(dx, 3)).clone();
    const FixationLoop::Step step = loop.Process(frame, {}, 0.04);
    lost += step.lock_lost ? 1 : 0;
    claimed += step.off_target ? 0 : 1;
    ++frames;
  }
  EXPECT_LE(claimed, 1) << "the first frame may still pass";
  EXPECT_GE(lost, frames - loop.options().lock_lost_frames);
}

// The other side: clean photos keep their lock over the same moves (no false lock loss).
TEST(FixationLoopTest, CleanPhotosKeepTheirLockOverTheSameMoves) {
  for (const char* name : {"aero1.jpg", "aero3.jpg", "fruits.jpg"}) {
    const cv::Mat scene = testing::LoadOpenCvPhoto(name);
    const cv::Rect window((scene.cols - 300) / 2, (scene.rows - 300) / 2, 300, 300);
    FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
    loop.SetReference(scene(window).clone());
    for (int dx = -40; dx <= 40; dx += 8) {
      const FixationLoop::Step step =
          loop.Process(scene(window + cv::Point(dx, 3)).clone(), {}, 0.04);
      EXPECT_FALSE(step.lock_lost)
          << name << " dx " << dx << " confidence " << step.match.confidence;
      EXPECT_TRUE(step.trusted) << name << " dx " << dx;
    }
  }
}

// Re-acquired far from the reference's view, the loop steers back at once but says the view
// is held again only once it is within lock_regain_px.
TEST(FixationLoopTest, AReacquiredViewCountsAsHeldOnlyOnceItIsBack) {
  FixationOptions o = Options();
  o.lock_lost_frames = 1;
  o.lock_regain_frames = 1;
  o.lock_regain_px = 10;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  ASSERT_TRUE(loop.Process(blank, {}, 0.04).lock_lost);
  const FixationLoop::Step far = loop.Process(testing::Translated(reference, 30, 0), {}, 0.04);
  EXPECT_TRUE(far.trusted) << "it steers back";
  EXPECT_TRUE(far.lock_lost) << "but 30 px off is not held";
  const FixationLoop::Step back = loop.Process(testing::Translated(reference, 4, 0), {}, 0.04);
  EXPECT_FALSE(back.lock_lost);
}

// Issue 9's honest lock: a right match that measures the view 20 px away is no lost lock,
// but the loop must not claim to hold the view; 3 px away it does.
TEST(FixationLoopTest, AViewMeasuredBeyondTheOffTargetDistanceIsSaidOffTarget) {
  FixationOptions o = Options();
  o.off_target_px = 8;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  const FixationLoop::Step near = loop.Process(testing::Translated(reference, 3, -2), {}, 0.04);
  ASSERT_TRUE(near.trusted);
  EXPECT_FALSE(near.off_target);
  const FixationLoop::Step far = loop.Process(testing::Translated(reference, 20, 0), {}, 0.04);
  ASSERT_TRUE(far.trusted) << "a right match, it steers";
  EXPECT_FALSE(far.lock_lost) << "the lock is not lost";
  EXPECT_TRUE(far.off_target) << "but 20 px off is not a held view";
}

// A kite's configuration searches X alone; pyr still reads the view across it (its cross
// range). That reading steers nothing, but a view it shows 11 px off in Y is not held: an
// X-only loop claimed such views (realistic world, 24 % of the frames grossly off, claimed).
TEST(FixationLoopTest, AViewReadOffAcrossASingleAxisSearchIsSaidOffTarget) {
  FixationOptions o = Options(SearchAxis::kX);
  o.off_target_px = 8;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  const FixationLoop::Step near = loop.Process(testing::Translated(reference, 2, 3), {}, 0.04);
  ASSERT_TRUE(near.trusted);
  EXPECT_FALSE(near.off_target);
  const FixationLoop::Step far = loop.Process(testing::Translated(reference, 2, 11), {}, 0.04);
  ASSERT_TRUE(far.trusted);
  ASSERT_NEAR(far.match.displacement.y, 11, 1) << "pyr reads the view across its X search";
  EXPECT_DOUBLE_EQ(far.targets.tilt_deg, 0.0) << "Y is not steered";
  EXPECT_TRUE(far.off_target) << "but 11 px off in Y is not a held view";
}

// aero1.jpg seen through a 640×480 frame, rolled by `roll_deg` and shifted by `shift_x` [px].
cv::Mat RolledView(double roll_deg, double shift_x) {
  return testing::RolledView("aero1.jpg", {640, 480}, roll_deg, {shift_x, 0});
}

// Issue 9's honest lock under roll: slice 8's patch sits ~160 px below the frame centre, so a
// 3° roll moves it 8.4 px while the centre stays; shifted 10 px the other way, the patch is
// held within 2 px and the centre is 10 px off. The claim judges the centre.
TEST(FixationLoopTest, AnOffCentrePatchHeldUnderRollIsSaidOffTargetWhenTheCentreIsNot) {
  for (const bool roll_aware : {true, false}) {
    FixationOptions o = Options();
    o.slice = 8;
    o.roll_aware_claim = roll_aware;
    FixationLoop loop(o, Pyr(), PlainP(), kLens);
    loop.SetReference(RolledView(0, 0));
    const FixationLoop::Step step = loop.Process(RolledView(3, 10), {}, 0.04);
    ASSERT_TRUE(step.trusted) << roll_aware;
    ASSERT_LT(std::hypot(step.match.displacement.x, step.match.displacement.y), 3)
        << "the patch is held";
    EXPECT_EQ(step.off_target, roll_aware) << "the centre is 10 px off";
    if (roll_aware) {
      EXPECT_NEAR(step.roll_deg, 3, 0.3);
    }
  }
}

// A camera rolling 0.5° a frame to 10° over smarties.png as the simulator shows it (enlarged
// 2.18×): the centre patch is dominated by sweets 70 px above its centre, so an upright
// reference is found sideways by ~70 px per radian (12 px at 10°), confidently, with the view
// not moved at all: held there, the view is lost silently (issue 9: 26 % of a flight grossly
// off and claimed). The reference turned by the roll read from the region around the patch
// is found where the view is.
TEST(FixationLoopTest, ARollingCameraIsFoundWhereTheViewIsNotWhereAFeatureSlid) {
  for (const bool tracking : {true, false}) {
    FixationOptions o = Options();
    o.roll_tracking.enabled = tracking;
    FixationLoop loop(o, Pyr(), PlainP(), kLens);
    const auto view = [](double roll_deg) {
      return testing::RolledView("smarties.png", {640, 480}, roll_deg, {0, 0}, 2.18);
    };
    loop.SetReference(view(0));
    FixationLoop::Step step;
    for (double roll = 0.5; roll <= 10; roll += 0.5) step = loop.Process(view(roll), {}, 0.04);
    ASSERT_TRUE(step.trusted) << tracking;
    const double miss = std::hypot(step.match.displacement.x, step.match.displacement.y);
    if (tracking) {
      EXPECT_LT(miss, 1.5);
      EXPECT_NEAR(step.tracked_roll_deg, 10, 1);
    } else {
      EXPECT_GT(miss, 8) << "the upright reference slides with the sweets";
      EXPECT_TRUE(std::isnan(step.tracked_roll_deg));
    }
  }
}

// The patch measured beyond the line (8.4 px) while the roll puts the centre 1 px off: the
// claim is not made on the roll read alone, which on a façade's repeats can be confidently
// wrong (building.jpg without roll read 2-3.5°, and frames 10-14 px off were claimed).
TEST(FixationLoopTest, APatchMeasuredBeyondTheLineIsNotClaimedWhateverTheRollRead) {
  FixationOptions o = Options();
  o.slice = 8;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  loop.SetReference(RolledView(0, 0));
  const FixationLoop::Step step = loop.Process(RolledView(-3, 1), {}, 0.04);
  ASSERT_TRUE(step.trusted);
  ASSERT_GT(std::hypot(step.match.displacement.x, step.match.displacement.y), 8);
  EXPECT_TRUE(step.off_target);
}

// The patch is held 3 px off, but a roll in range could put the centre 16 px away, and the
// roll cannot be read (a margin that leaves no inside to compare): the loop cannot vouch for
// the centre, so it does not claim the view; judging the patch alone, it would.
TEST(FixationLoopTest, AClaimThatNeedsAnUnreadableRollIsNotMade) {
  for (const bool roll_aware : {true, false}) {
    FixationOptions o = Options();
    o.slice = 8;
    o.roll_aware_claim = roll_aware;
    o.roll.margin_px = 49;  // of a 100 px patch: nothing left to compare
    FixationLoop loop(o, Pyr(), PlainP(), kLens);
    loop.SetReference(RolledView(0, 0));
    const FixationLoop::Step step = loop.Process(RolledView(0, 3), {}, 0.04);
    ASSERT_TRUE(step.trusted) << roll_aware;
    EXPECT_EQ(step.off_target, roll_aware);
    EXPECT_TRUE(std::isnan(step.roll_deg));
  }
}

TEST(FixationLoopTest, AnUntrustedFrameIsNeverClaimedOnTarget) {
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  ConfirmLock(loop, reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  const FixationLoop::Step step = loop.Process(blank, {}, 0.04);
  ASSERT_FALSE(step.lock_lost) << "a confirmed lock rides out one untrusted frame";
  EXPECT_TRUE(step.off_target);
}

// A confirmed lock rides out an untrusted frame and steers by the trusted frames after it,
// but says it holds the view only once it stands clear again (lock_regain_frames clear frames
// in a row): frames that barely pass the trust threshold between untrusted ones were claimed
// 10-13 px off (baboon.jpg after SSP, realistic world).
TEST(FixationLoopTest, ALockRidingOutUntrustedFramesIsClaimedOnlyOnceItStandsClearAgain) {
  const FixationOptions o = Options();
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  ConfirmLock(loop, reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  ASSERT_FALSE(loop.Process(blank, {}, 0.04).lock_lost);
  for (int k = 1; k < o.lock_regain_frames; ++k) {
    const FixationLoop::Step step = loop.Process(reference, {}, 0.04);
    EXPECT_TRUE(step.trusted) << "frame " << k << " steers";
    EXPECT_TRUE(step.off_target) << "frame " << k << " is not yet vouched for";
    EXPECT_TRUE(step.riding_out) << "frame " << k;
  }
  const FixationLoop::Step clear = loop.Process(reference, {}, 0.04);
  EXPECT_FALSE(clear.off_target);
  EXPECT_FALSE(clear.riding_out);
}

TEST(FixationLoopTest, RejectsANonPositiveOffTargetDistance) {
  FixationOptions o = Options();
  o.off_target_px = 0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("off-target distance"), std::string::npos) << error;
}

TEST(FixationLoopTest, RejectsARegainConfidenceBelowTheLostOne) {
  FixationOptions o = Options();
  o.lock_regain_confidence = o.lock_lost_confidence - 0.05;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("lock-regain confidence"), std::string::npos) << error;
}

TEST(FixationLoopTest, ALostLockIsReacquiredOnlyAfterARunOfTrustedFrames) {
  FixationOptions o = Options();
  o.lock_lost_frames = 2;
  o.lock_regain_frames = 3;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat reference = Texture();
  loop.SetReference(reference);
  const cv::Mat blank(300, 300, CV_8UC3, cv::Scalar::all(128));
  loop.Process(blank, {}, 0.04);
  ASSERT_TRUE(loop.Process(blank, {}, 0.04).lock_lost);
  // The stored reference is back in view, shifted: the first good frames are searched as a
  // re-acquisition and do not steer yet (a lucky frame on a repetitive scene must not).
  cv::Mat shifted;
  cv::warpAffine(reference, shifted, cv::Matx23d(1, 0, 6, 0, 1, 0), reference.size(),
                 cv::INTER_LINEAR, cv::BORDER_REFLECT);
  for (int k = 0; k < 2; ++k) {
    const FixationLoop::Step step = loop.Process(shifted, {2.0, 0.0}, 0.04);
    EXPECT_TRUE(step.reacquiring);
    EXPECT_TRUE(step.lock_lost);
    EXPECT_FALSE(step.trusted);
    EXPECT_DOUBLE_EQ(step.targets.pan_deg, 2.0);  // held
  }
  const FixationLoop::Step regained = loop.Process(shifted, {2.0, 0.0}, 0.04);
  EXPECT_FALSE(regained.lock_lost);
  EXPECT_TRUE(regained.trusted);
  EXPECT_NEAR(regained.match.displacement.x, 6.0, 0.5);
  EXPECT_GT(regained.targets.pan_deg, 2.0);  // steering again
}

TEST(FixationLoopTest, FollowSumsTheFrameToFrameSteps) {
  FixationOptions o = Options();
  o.reference = FixationOptions::Reference::kPrevious;
  o.follow_decay_frames = 1e12;  // no leak
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat scene = Texture();
  loop.SetReference(scene);
  // The view drifts 3 px per frame; each frame is compared with the previous one only.
  for (int k = 1; k <= 4; ++k) {
    const FixationLoop::Step step = loop.Process(testing::Translated(scene, 3 * k, 0), {}, 0.04);
    EXPECT_NEAR(step.match.displacement.x, 3, 0.2) << "frame " << k;
    EXPECT_NEAR(step.targets.pan_deg, 0.1 * 3 * k, 0.05) << "frame " << k;
  }
}

TEST(FixationLoopTest, GreyReferenceIsCopiedNotShared) {
  FixationOptions o = Options();
  o.sampling = {SamplingKind::kAll};
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  const cv::Mat scene = testing::SmoothTexture({300, 300}, 12, 3.0);
  cv::Mat buffer = scene.clone();  // a capture buffer the caller reuses
  loop.SetReference(buffer);
  testing::Translated(scene, 9, 0).copyTo(buffer);
  const FixationLoop::Step step = loop.Process(scene, {}, 0.04);
  EXPECT_NEAR(step.match.displacement.x, 0, 0.2);
}

TEST(FixationLoopTest, PatchOutsideTheFrameIsRejected) {
  FixationOptions o = Options();
  o.patch_size = 400;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  EXPECT_THROW(loop.SetReference(Texture()), std::invalid_argument);
}

TEST(FixationLoopTest, RejectsASliceBeyondTheSliceCount) {
  FixationOptions o;
  o.slice = 10;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_THROW(FixationLoop(o, Pyr(), PlainP(), kLens), std::invalid_argument);
}

// The sign chain end to end on the simulated platform: a thesis-style calibration (servo
// moves → measured displacements → CalibrateAxis) turned into the controller's gain is
// positive, and with it plain P holds a swinging view.
TEST(FixationLoopTest, CalibrationOnThePlatformGivesAPositiveGainThatHoldsTheView) {
  SimulatedPlatformOptions po;
  po.kite.amplitude_px = 0;
  po.kite.jitter_sigma_px = 0;
  for (SimulatedServoOptions* servo : {&po.pan, &po.tilt}) servo->latency_frames = 0;
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  std::vector<CalibrationSample> pan_samples, tilt_samples;
  {
    SimulatedPlatform platform(scene, po);
    FixationLoop probe(Options(), Pyr(), PlainP(), kLens);
    probe.SetReference(platform.Capture());
    for (const double move : CalibrationMoves(4, 1)) {  // [deg]
      platform.CommandPan(move);
      platform.CommandTilt(move);
      for (int k = 0; k < 4; ++k) platform.Step();  // rate limit: 3°/frame
      const cv::Point2d d = probe.Process(platform.Capture(), {}, 0.04).match.displacement;
      pan_samples.push_back({move, d.x});
      tilt_samples.push_back({move, d.y});
    }
  }
  const LensCalibration lens = LensCalibration::FromCalibrationMoves(CalibrateAxis(pan_samples),
                                                                     CalibrateAxis(tilt_samples));
  EXPECT_NEAR(lens.pan_deg_per_px, 1 / po.px_per_deg, 0.005);
  EXPECT_NEAR(lens.tilt_deg_per_px, 1 / po.px_per_deg, 0.005);

  po.kite.amplitude_px = 30;
  po.kite.period_frames = 80;  // slow enough for plain P at latency 0
  SimulatedPlatform platform(scene, po);
  FixationLoop loop(Options(), Pyr(),
                    std::make_unique<ProportionalController>(ControllerGains{}, lens), lens);
  loop.SetReference(platform.Capture());
  double worst = 0;
  for (int t = 1; t <= 80; ++t) {
    platform.Step();
    const SimulatedFrame frame = platform.CaptureFrame();
    const FixationLoop::Step step =
        loop.Process(frame.image, {frame.pan_deg, frame.tilt_deg}, 0.04);
    platform.CommandPan(step.targets.pan_deg);
    platform.CommandTilt(step.targets.tilt_deg);
    if (t > 10) worst = std::max(worst, cv::norm(platform.ViewOffset()));
  }
  // Open loop the view swings ±30 px; at latency 0 P trails by one frame, ≤ 2.4 px here.
  EXPECT_LT(worst, 4.0);
}

// fruits.jpg seen through a 300×300 window moved by (dx, dy), its brightness times `gain`
// (an auto-exposure step), as a BGR frame.
cv::Mat FruitsFrame(int dx, int dy, double gain = 1.0) {
  static const cv::Mat photo = testing::LoadOpenCvPhoto("fruits.jpg");
  cv::Mat frame;
  photo(cv::Rect(140 - dx, 60 - dy, 300, 300)).convertTo(frame, CV_8U, gain);
  return frame;
}

// The realistic world's silent wrong lock after SSP (issue 9): the reference was stored at a
// dim exposure and the frame is 1.6 × brighter; uncompensated, pyr's finer levels walked
// 10–12 px off the view at a trusted confidence.
TEST(FixationLoopTest, AnExposureStepSinceTheReferenceIsCompensatedBeforeTheSearch) {
  FixationLoop loop(Options(), Pyr(), PlainP(), kLens);
  loop.SetReference(FruitsFrame(0, 0));
  const FixationLoop::Step step = loop.Process(FruitsFrame(5, -3, 1.6), {}, 0.04);
  EXPECT_NEAR(step.exposure_gain, 1 / 1.6, 0.05);
  ASSERT_TRUE(step.trusted);
  EXPECT_NEAR(step.match.displacement.x, 5, 0.5);
  EXPECT_NEAR(step.match.displacement.y, -3, 0.5);
}

TEST(FixationLoopTest, WithoutCompensationAnExposureStepIsSaidOffTargetNotHeld) {
  FixationOptions o = Options();
  o.compensate_exposure = false;
  FixationLoop loop(o, Pyr(), PlainP(), kLens);
  loop.SetReference(FruitsFrame(0, 0));
  const FixationLoop::Step step = loop.Process(FruitsFrame(5, -3, 1.6), {}, 0.04);
  EXPECT_EQ(step.exposure_gain, 1.0);
  EXPECT_FALSE(step.trusted);
  EXPECT_TRUE(step.off_target);
}

}  // namespace
}  // namespace kapfix
