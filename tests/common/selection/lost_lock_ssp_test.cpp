#include "common/selection/lost_lock_ssp.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <vector>

#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr int kWait = 4;
constexpr int kRun = 21;

// A free swing over a scene whose middle band (slice 5 of 9, the centre) is flat: the patch a
// first-frame fixation takes there cannot be tracked.
std::vector<cv::Mat> Swing(int frames) {
  cv::Mat scene = testing::SmoothTexture({360, 300}, 7);
  scene.rowRange(120, 180).setTo(cv::Scalar(128));
  return testing::SwingFrames(scene, {300, 300}, testing::PendulumPositions(frames, 20.0, 40.0));
}

LostLockSspOptions Options() {
  LostLockSspOptions options;
  options.after_frames = kWait;
  options.run_frames = kRun;
  options.selection.search.range = 20;
  return options;
}

// The plane See asks for.
std::function<cv::Mat()> Plane(const cv::Mat& frame) {
  return [&frame] { return frame; };
}

const SearchStrategy& Exhaustive() {
  static const auto strategy = MakeSearchStrategy("all", nullptr);
  return *strategy;
}

TEST(LostLockSspTest, RunsNothingWhileTheLockIsHeld) {
  LostLockSsp ssp(Exhaustive(), Options());
  for (const cv::Mat& frame : Swing(kWait + kRun + 5)) {
    EXPECT_FALSE(ssp.See(/*lock_lost=*/false, Plane(frame)).has_value());
    EXPECT_FALSE(ssp.running());
  }
}

TEST(LostLockSspTest, ALockLostLongEnoughGetsSspOverTheFramesAfterTheWait) {
  const std::vector<cv::Mat> frames = Swing(kWait + kRun);
  LostLockSsp ssp(Exhaustive(), Options());
  std::optional<SliceSelection> result;
  for (std::size_t t = 0; t < frames.size(); ++t) {
    result = ssp.See(/*lock_lost=*/true, Plane(frames[t]));
    EXPECT_EQ(ssp.running(), t >= kWait && t + 1 < frames.size()) << "frame " << t;
    if (t + 1 < frames.size()) {
      EXPECT_FALSE(result.has_value()) << "frame " << t;
    }
  }
  ASSERT_TRUE(result.has_value());
  // SSP itself over the frames after the wait.
  const std::vector<cv::Mat> run(frames.begin() + kWait, frames.end());
  const SliceSelection expected = SelectSlice(run, Exhaustive(), Options().selection);
  EXPECT_EQ(result->ranking, expected.ranking);
  EXPECT_EQ(result->frames_used, kRun);
  EXPECT_NE(result->best_slice, 5) << "the flat centre band cannot be the recommended slice";
}

TEST(LostLockSspTest, ALockRegainedDropsTheRunAndTheNextLossWaitsAgain) {
  const std::vector<cv::Mat> frames = Swing(3 * kWait + kRun);
  LostLockSsp ssp(Exhaustive(), Options());
  std::size_t t = 0;
  for (; t < kWait + 3; ++t) ssp.See(true, Plane(frames[t]));
  ASSERT_TRUE(ssp.running());
  EXPECT_FALSE(ssp.See(/*lock_lost=*/false, Plane(frames[t++])).has_value());
  EXPECT_FALSE(ssp.running());
  EXPECT_EQ(ssp.lost_frames(), 0);
  for (int k = 0; k < kWait; ++k) {
    ssp.See(true, Plane(frames[t++]));
    EXPECT_FALSE(ssp.running()) << "lost frame " << k + 1 << " of the new stretch";
  }
  ssp.See(true, Plane(frames[t++]));
  EXPECT_TRUE(ssp.running());
}

TEST(LostLockSspTest, AStillLostLockWaitsAWholeStretchBeforeTheNextRun) {
  const std::vector<cv::Mat> frames = Swing(kWait + kRun + kWait + 1);
  LostLockSsp ssp(Exhaustive(), Options());
  int results = 0;
  for (std::size_t t = 0; t < kWait + kRun; ++t) results += ssp.See(true, Plane(frames[t])) ? 1 : 0;
  ASSERT_EQ(results, 1);
  for (std::size_t t = kWait + kRun; t < frames.size() - 1; ++t) {
    ssp.See(true, Plane(frames[t]));
    EXPECT_FALSE(ssp.running());
  }
  ssp.See(true, Plane(frames.back()));
  EXPECT_TRUE(ssp.running());
}

TEST(LostLockSspTest, ANoughtWaitIsOff) {
  LostLockSspOptions options = Options();
  options.after_frames = 0;
  LostLockSsp ssp(Exhaustive(), options);
  for (const cv::Mat& frame : Swing(kRun + 5)) {
    EXPECT_FALSE(ssp.See(true, Plane(frame)).has_value());
    EXPECT_FALSE(ssp.running());
  }
}

TEST(LostLockSspTest, RefusesARunOfFewerThanTwoFramesAndANegativeWait) {
  LostLockSspOptions options = Options();
  options.run_frames = 1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("≥ 2 frames"), std::string::npos) << error;
  EXPECT_THROW(LostLockSsp(Exhaustive(), options), std::invalid_argument);
  options = Options();
  options.after_frames = -1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("≥ 0 frames"), std::string::npos) << error;
}

}  // namespace
}  // namespace kapfix
