// The aperture problem in the fixation loop: a match sure along one axis and not the other.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>

#include "common/control/proportional_controller.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr LensCalibration kLens{0.1, 0.1};  // [deg/px]

// Answers each search with the next scripted result (the last one once the script ends).
class ScriptedSearch final : public SearchStrategy {
 public:
  explicit ScriptedSearch(std::deque<SearchResult> script) : script_(std::move(script)) {}
  std::string name() const override { return "scripted"; }
  SearchResult Search(const ReferencePatch&, const cv::Mat&, const SearchOptions&) const override {
    const SearchResult next = script_.front();
    if (script_.size() > 1) script_.pop_front();
    return next;
  }

 private:
  mutable std::deque<SearchResult> script_;
};

SearchResult Match(cv::Point2d displacement, double confidence_x, double confidence_y) {
  SearchResult r;
  r.found = true;
  r.displacement = displacement;
  r.shift = {static_cast<int>(std::lround(displacement.x)),
             static_cast<int>(std::lround(displacement.y))};
  r.confidence_x = confidence_x;
  r.confidence_y = confidence_y;
  r.confidence = std::min(confidence_x, confidence_y);
  return r;
}

// Sure along X (0.8), hardly along Y (0.05), as a patch of vertical stripes is.
SearchResult SureAlongXOnly() { return Match({3, 7}, 0.8, 0.05); }

// A loop whose searches answer `script`, steered by plain P over kLens, on the reference of a
// textured frame; both axes searched.
struct ScriptedLoop {
  explicit ScriptedLoop(std::deque<SearchResult> script)
      : loop(Options(), std::make_shared<ScriptedSearch>(std::move(script)), PlainP(), kLens) {
    loop.SetReference(frame);
  }
  static FixationOptions Options() {
    FixationOptions o;
    o.search.axis = SearchAxis::kBoth;
    return o;
  }
  static std::unique_ptr<Controller> PlainP() {
    ControllerGains gains;
    gains.dead_band_px = 0;
    return std::make_unique<ProportionalController>(gains, kLens);
  }
  FixationLoop::Step Next() { return loop.Process(frame, {1.0, 2.0}, 0.04); }

  cv::Mat frame = [] {
    cv::Mat bgr;
    cv::cvtColor(testing::SmoothTexture({300, 300}, 12, 3.0), bgr, cv::COLOR_GRAY2BGR);
    return bgr;
  }();
  FixationLoop loop;
};

std::deque<SearchResult> ConfirmedThen(const SearchResult& then, int clear_frames = 3) {
  std::deque<SearchResult> script(static_cast<std::size_t>(clear_frames), Match({0, 0}, 0.9, 0.9));
  script.push_back(then);
  return script;
}

TEST(FixationLoopApertureTest, AConfirmedLockRidesOnTheAxisItsMatchIsSureOf) {
  ScriptedLoop scripted(ConfirmedThen(SureAlongXOnly()));
  for (int k = 0; k < 3; ++k) ASSERT_FALSE(scripted.Next().lock_lost);
  // Far more frames than lock_lost_frames (5): none of them is untrusted along X.
  for (int k = 0; k < 20; ++k) {
    const FixationLoop::Step step = scripted.Next();
    ASSERT_FALSE(step.lock_lost) << "frame " << k;
    EXPECT_TRUE(step.trusted);
    EXPECT_TRUE(step.partial);
    EXPECT_TRUE(step.trusted_x);
    EXPECT_FALSE(step.trusted_y);
  }
}

TEST(FixationLoopApertureTest, TheSureAxisIsSteeredAndTheOtherHeld) {
  ScriptedLoop scripted(ConfirmedThen(SureAlongXOnly()));
  for (int k = 0; k < 3; ++k) scripted.Next();
  const FixationLoop::Step step = scripted.Next();
  EXPECT_NEAR(step.targets.pan_deg, 1.0 + 3 * 0.1, 1e-9);  // X's 3 px corrected
  EXPECT_DOUBLE_EQ(step.targets.tilt_deg, 2.0);            // Y's unsure 7 px not
}

TEST(FixationLoopApertureTest, AFrameSteeredOnOneAxisIsNeverClaimedOnTarget) {
  // Within off_target_px on both axes, so only the unsure axis keeps it from being claimed.
  ScriptedLoop scripted(ConfirmedThen(Match({1, 1}, 0.8, 0.05)));
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(scripted.Next().off_target);
  EXPECT_TRUE(scripted.Next().off_target);
}

TEST(FixationLoopApertureTest, ALockNotYetConfirmedNeedsBothAxes) {
  ScriptedLoop scripted(ConfirmedThen(SureAlongXOnly(), /*clear_frames=*/1));
  EXPECT_FALSE(scripted.Next().lock_lost);
  const FixationLoop::Step step = scripted.Next();
  EXPECT_FALSE(step.trusted);
  EXPECT_FALSE(step.partial);
  EXPECT_DOUBLE_EQ(step.targets.pan_deg, 1.0);  // neither axis steered
}

TEST(FixationLoopApertureTest, AFrameUnsureOnBothAxesStillCountsTowardsALostLock) {
  ScriptedLoop scripted(ConfirmedThen(Match({3, 7}, 0.1, 0.05)));
  for (int k = 0; k < 3; ++k) scripted.Next();
  bool lost = false;
  for (int k = 0; k < scripted.loop.options().lock_lost_frames; ++k)
    lost = scripted.Next().lock_lost;
  EXPECT_TRUE(lost);
}

}  // namespace
}  // namespace kapfix
