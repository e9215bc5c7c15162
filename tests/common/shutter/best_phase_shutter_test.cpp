#include "common/shutter/best_phase_shutter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

namespace kapfix {
namespace {

constexpr std::int64_t kFrameUs = 33333;  // 30 fps

// A forecaster that knows the path: its forecasts are the scripted offsets themselves.
class ScriptedForecaster final : public ViewForecaster {
 public:
  explicit ScriptedForecaster(std::function<cv::Point2d(int)> path) : path_(std::move(path)) {}
  void Observe(const ShutterFrame& /*frame*/) override { ++newest_; }
  bool trained() const override { return trained_; }
  cv::Point2d Forecast(int frames) const override { return path_(newest_ + frames); }
  cv::Point2d error_rms() const override { return {0, 0}; }
  std::optional<double> period_frames() const override { return period_; }

  bool trained_ = true;
  std::optional<double> period_;

 private:
  std::function<cv::Point2d(int)> path_;
  int newest_ = -1;
};

ShutterFrame Frame(int index, cv::Point2d offset, bool trusted = true) {
  ShutterFrame frame;
  frame.time_us = index * kFrameUs;
  frame.offset_px = offset;
  frame.trusted = trusted;
  return frame;
}

BestPhaseShutterOptions BestPhase(double window_s) {
  BestPhaseShutterOptions options;
  options.mode = ShutterMode::kBestPhase;
  options.window_s = window_s;
  options.frame_period_s = kFrameUs / 1e6;
  return options;
}

// Runs frames 0… of `path`, requesting a photo before frame `request_at`; the frame it fired
// on and the shot.
std::optional<std::pair<int, ShutterShot>> RunFrames(
    BestPhaseShutter& shutter, const std::function<cv::Point2d(int)>& path, int request_at,
    int frames, const std::function<bool(int)>& trusted = [](int) { return true; }) {
  for (int i = 0; i < frames; ++i) {
    if (i == request_at) shutter.Request();
    if (auto shot = shutter.OnFrame(Frame(i, path(i), trusted(i)))) {
      return std::make_pair(i, *shot);
    }
  }
  return std::nullopt;
}

// A swing of the residual with a 20-frame period: fastest at the zero crossings (frames 0,
// 10, …), slowest between frames 4–5 and 5–6 at the turning point.
cv::Point2d Swing(int frame) { return {10.0 * std::sin(2 * std::numbers::pi * frame / 20.0), 0.0}; }

TEST(BestPhaseShutterTest, FiresOnTheFrameOfTheQuietPhase) {
  ScriptedForecaster forecaster(Swing);
  BestPhaseShutterOptions options = BestPhase(0.9);
  options.offset_weight = 0;  // speed alone
  BestPhaseShutter shutter(forecaster, options);
  const auto fired = RunFrames(shutter, Swing, 1, 60);
  ASSERT_TRUE(fired);
  // Frames 5 and 6 are equally slow: the first of them, decided on itself.
  EXPECT_EQ(fired->first, 5);
  EXPECT_NEAR(fired->second.speed_px_per_frame, 10.0 * (1 - std::sin(0.4 * std::numbers::pi)),
              1e-9);
  EXPECT_NEAR(fired->second.wait_s, 4 * kFrameUs / 1e6, 1e-9);
  EXPECT_NE(fired->second.reason.find("quietest predicted moment"), std::string::npos);
  EXPECT_FALSE(fired->second.lock_lost);
}

TEST(BestPhaseShutterTest, PrefersAnOnTargetFrameAtTheSameSpeed) {
  // Steady drift of 1 px per frame from −16 px: the speed never changes, the offset comes
  // within the 10 px on-target tolerance at frame 6.
  const auto drift = [](int frame) { return cv::Point2d(frame - 16.0, 0.0); };
  ScriptedForecaster forecaster(drift);
  BestPhaseShutter shutter(forecaster, BestPhase(1.0));
  const auto fired = RunFrames(shutter, drift, 1, 60);
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 6);
  EXPECT_NEAR(fired->second.offset_px, 10.0, 1e-9);
}

TEST(BestPhaseShutterTest, AnOnTargetOffsetDoesNotBuySmear) {
  // Near the reference (±0.25 px) but moving 0.5 px per frame, except frame 11: 8.1 px off,
  // still on target, and moving 0.1 px. Only the smear shows in the photo, so frame 11 it is
  // (weighing the whole offset, 0.1 px per px, would take frame 1 at once).
  const auto path = [](int frame) {
    if (frame == 10) return cv::Point2d(8.0, 0.0);
    if (frame == 11) return cv::Point2d(8.1, 0.0);
    return cv::Point2d(frame % 2 == 0 ? 0.25 : -0.25, 0.0);
  };
  ScriptedForecaster forecaster(path);
  BestPhaseShutter shutter(forecaster, BestPhase(1.0));
  const auto fired = RunFrames(shutter, path, 1, 60);
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 11);
  EXPECT_NEAR(fired->second.speed_px_per_frame, 0.1, 1e-9);
}

TEST(BestPhaseShutterTest, UntrustedLockThroughTheWindowFiresAtItsEnd) {
  ScriptedForecaster forecaster(Swing);
  BestPhaseShutter shutter(forecaster, BestPhase(0.5));  // 15 frames
  const auto fired = RunFrames(shutter, Swing, 2, 60, [](int frame) { return frame < 2; });
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 2 + 15);
  EXPECT_TRUE(fired->second.lock_lost);
  EXPECT_NE(fired->second.reason.find("lock not trusted in the window"), std::string::npos);
}

TEST(BestPhaseShutterTest, WithoutATrainedPredictorFiresAtOnce) {
  ScriptedForecaster forecaster(Swing);
  forecaster.trained_ = false;
  BestPhaseShutter shutter(forecaster, BestPhase(1.0));
  const auto fired = RunFrames(shutter, Swing, 1, 60);
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 1);
  EXPECT_NE(fired->second.reason.find("no trained predictor"), std::string::npos);
}

TEST(BestPhaseShutterTest, IntervalModeFiresAtOnce) {
  ScriptedForecaster forecaster(Swing);
  BestPhaseShutterOptions options = BestPhase(1.0);
  options.mode = ShutterMode::kInterval;
  BestPhaseShutter shutter(forecaster, options);
  const auto fired = RunFrames(shutter, Swing, 1, 60);
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 1);
  EXPECT_NEAR(fired->second.wait_s, 0.0, 1e-12);
}

TEST(BestPhaseShutterTest, WindowOfOneSwingPeriodEndsAfterIt) {
  // Slower and slower for ever: the forecast always says "wait", so only the window's end
  // (one 12-frame period) makes it fire.
  const auto slowing = [](int frame) { return cv::Point2d(100.0 * std::sqrt(frame + 1.0), 0); };
  ScriptedForecaster forecaster(slowing);
  forecaster.period_ = 12;
  BestPhaseShutterOptions options = BestPhase(0);
  options.offset_weight = 0;
  BestPhaseShutter shutter(forecaster, options);
  const auto fired = RunFrames(shutter, slowing, 3, 100);
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 3 + 12);
  EXPECT_EQ(fired->second.reason, "window end");
}

TEST(BestPhaseShutterTest, WindowOfOnePeriodIsCapped) {
  const auto slowing = [](int frame) { return cv::Point2d(100.0 * std::sqrt(frame + 1.0), 0); };
  ScriptedForecaster forecaster(slowing);
  forecaster.period_ = 1000;  // 33 s
  BestPhaseShutterOptions options = BestPhase(0);
  options.window_cap_s = 1.0;  // 30 frames
  options.offset_weight = 0;
  BestPhaseShutter shutter(forecaster, options);
  const auto fired = RunFrames(shutter, slowing, 0, 100);
  ASSERT_TRUE(fired);
  EXPECT_EQ(fired->first, 30);
}

TEST(BestPhaseShutterTest, WindowLongerThanTheCapIsRefused) {
  BestPhaseShutterOptions options = BestPhase(12);
  options.window_cap_s = 10;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("longer than its cap"), std::string::npos) << error;
  ScriptedForecaster forecaster(Swing);
  EXPECT_THROW(BestPhaseShutter(forecaster, options), std::invalid_argument);
}

TEST(BestPhaseShutterTest, ExposureMustBePositive) {
  BestPhaseShutterOptions options = BestPhase(1);
  options.exposure_ms = 0;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("exposure must be positive"), std::string::npos) << error;
}

TEST(BestPhaseShutterTest, NegativeOnTargetToleranceIsRefused) {
  BestPhaseShutterOptions options = BestPhase(1);
  options.on_target_px = -1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("on-target tolerance"), std::string::npos) << error;
}

}  // namespace
}  // namespace kapfix
