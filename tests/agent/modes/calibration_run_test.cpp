// CalibrationRun against a fake camera whose view shifts by k px per degree of the servo
// angle commanded a frame earlier: the fit recovers the lens's degrees per pixel.
#include "agent/modes/calibration_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "tests/support/test_images.hpp"

namespace kapfix::agent {
namespace {

constexpr double kPxPerDeg = 5.0;
const cv::Size kView(160, 120);
const cv::Point kOrigin(50, 60);  // [px] where the view sits in the texture at 0°

// A camera on the servos: the view is a crop of a texture moved by k px per degree of the
// angles commanded `latency` frames before (a window moving right moves the content left).
class ShiftingCamera {
 public:
  ShiftingCamera(double px_per_deg, int latency, ServoTargets start)
      : texture_(kapfix::testing::SmoothTexture({300, 260}, 11)),
        px_per_deg_(px_per_deg),
        latency_(latency),
        sent_{start} {}

  cv::Mat View() const {
    const auto index = static_cast<std::ptrdiff_t>(sent_.size()) - latency_;
    const ServoTargets& seen = sent_[static_cast<std::size_t>(std::max<std::ptrdiff_t>(index, 0))];
    const cv::Point origin(kOrigin.x + static_cast<int>(std::lround(px_per_deg_ * seen.pan_deg)),
                           kOrigin.y + static_cast<int>(std::lround(px_per_deg_ * seen.tilt_deg)));
    return texture_(cv::Rect(origin, kView)).clone();
  }
  void Command(const ServoTargets& targets) { sent_.push_back(targets); }

 private:
  cv::Mat texture_;
  double px_per_deg_;
  int latency_;
  std::vector<ServoTargets> sent_;
};

CalibrationRunOptions Options(ServoTargets park = {1.0, -2.0}) {
  CalibrationRunOptions o;
  o.span_deg = 4.0;  // ±20 px at 5 px/deg
  o.step_deg = 0.8;
  o.settle_frames = 3;
  o.patch = cv::Rect(60, 40, 40, 40);
  o.sampling.kind = SamplingKind::kAll;
  o.search.range = 30;
  o.search.subpixel = true;
  o.park = park;
  return o;
}

std::shared_ptr<const SearchStrategy> Exhaustive() {
  std::string error;
  std::shared_ptr<const SearchStrategy> strategy = MakeSearchStrategy("all", &error);
  EXPECT_NE(strategy, nullptr) << error;
  return strategy;
}

// Steps the run on the camera until it finishes (or a bound of frames passes).
void RunToTheEnd(CalibrationRun& run, ShiftingCamera& camera) {
  for (int frame = 0; frame < 1000 && !run.finished(); ++frame) {
    camera.Command(run.Step(camera.View()));
  }
}

TEST(CalibrationRunTest, FitPanRecoversTheDegreesPerPixel) {
  const auto strategy = Exhaustive();
  CalibrationRun run(Options(), *strategy);
  ShiftingCamera camera(kPxPerDeg, 1, Options().park);
  RunToTheEnd(run, camera);
  ASSERT_TRUE(run.finished());
  // A move of +1° moves the content by −k px: −1/k degrees per pixel of displacement.
  EXPECT_NEAR(run.FitPan().units_per_px_fit, -1.0 / kPxPerDeg, 0.05 / kPxPerDeg);
}

TEST(CalibrationRunTest, FitTiltRecoversTheDegreesPerPixel) {
  const auto strategy = Exhaustive();
  CalibrationRun run(Options(), *strategy);
  ShiftingCamera camera(kPxPerDeg, 1, Options().park);
  RunToTheEnd(run, camera);
  ASSERT_TRUE(run.finished());
  EXPECT_NEAR(run.FitTilt().units_per_px_fit, -1.0 / kPxPerDeg, 0.05 / kPxPerDeg);
}

TEST(CalibrationRunTest, ServoLatencyWithinTheSettleTimeDoesNotBiasTheFit) {
  const auto strategy = Exhaustive();
  CalibrationRun run(Options(), *strategy);
  ShiftingCamera camera(kPxPerDeg, 3, Options().park);  // as long as settle_frames
  RunToTheEnd(run, camera);
  ASSERT_TRUE(run.finished());
  EXPECT_NEAR(run.FitPan().units_per_px_fit, -1.0 / kPxPerDeg, 0.05 / kPxPerDeg);
  EXPECT_NEAR(run.FitTilt().units_per_px_fit, -1.0 / kPxPerDeg, 0.05 / kPxPerDeg);
}

TEST(CalibrationRunTest, EachMoveIsCommandedRelativeToPark) {
  const auto strategy = Exhaustive();
  const ServoTargets park{1.0, -2.0};
  CalibrationRun run(Options(park), *strategy);
  ShiftingCamera camera(kPxPerDeg, 1, park);
  double lowest_pan = park.pan_deg;
  double highest_pan = park.pan_deg;
  for (int frame = 0; frame < 1000 && !run.finished(); ++frame) {
    const ServoTargets command = run.Step(camera.View());
    lowest_pan = std::min(lowest_pan, command.pan_deg);
    highest_pan = std::max(highest_pan, command.pan_deg);
    camera.Command(command);
  }
  EXPECT_NEAR(lowest_pan, park.pan_deg - 4.0, 1e-9);
  EXPECT_NEAR(highest_pan, park.pan_deg + 4.0, 1e-9);
}

TEST(CalibrationRunTest, ProgressCountsEveryMoveOfBothAxes) {
  const auto strategy = Exhaustive();
  CalibrationRun run(Options(), *strategy);
  EXPECT_EQ(run.moves_total(), static_cast<int>(2 * CalibrationMoves(4.0, 0.8).size()));
  EXPECT_EQ(run.moves_done(), 0);
  ShiftingCamera camera(kPxPerDeg, 1, Options().park);
  int previous = 0;
  for (int frame = 0; frame < 1000 && !run.finished(); ++frame) {
    camera.Command(run.Step(camera.View()));
    EXPECT_GE(run.moves_done(), previous);
    EXPECT_LE(run.moves_done(), previous + 1);
    if (!run.finished()) {
      EXPECT_LT(run.moves_done(), run.moves_total());
    }
    previous = run.moves_done();
  }
  ASSERT_TRUE(run.finished());
  EXPECT_EQ(run.moves_done(), run.moves_total());
}

TEST(CalibrationRunTest, FinishedRunHoldsPark) {
  const auto strategy = Exhaustive();
  const ServoTargets park{1.0, -2.0};
  CalibrationRun run(Options(park), *strategy);
  ShiftingCamera camera(kPxPerDeg, 1, park);
  RunToTheEnd(run, camera);
  ASSERT_TRUE(run.finished());
  const ServoTargets after = run.Step(camera.View());
  EXPECT_DOUBLE_EQ(after.pan_deg, park.pan_deg);
  EXPECT_DOUBLE_EQ(after.tilt_deg, park.tilt_deg);
}

TEST(CalibrationRunTest, AViewThatDoesNotMoveGivesNoFit) {
  const auto strategy = Exhaustive();
  CalibrationRun run(Options(), *strategy);
  ShiftingCamera camera(0.0, 1, Options().park);  // the servos turn, the view does not
  RunToTheEnd(run, camera);
  ASSERT_TRUE(run.finished());
  EXPECT_THROW(run.FitPan(), std::invalid_argument);
}

TEST(CalibrationRunTest, ZeroStepIsRefused) {
  const auto strategy = Exhaustive();
  CalibrationRunOptions options = Options();
  options.step_deg = 0;
  EXPECT_THROW(CalibrationRun run(options, *strategy), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix::agent
