#include "groundstation/status/lock_quality.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace kapfix::station {
namespace {

constexpr std::int64_t kFrameUs = 33'333;  // [µs] 30 fps

kapfix::v1::Telemetry Sample(std::int64_t frame, double x_px, float confidence = 0.8F,
                             bool lock_lost = false,
                             kapfix::v1::Mode mode = kapfix::v1::MODE_FIXATE) {
  kapfix::v1::Telemetry t;
  t.mutable_header()->set_capture_time_us(1'000'000'000 + frame * kFrameUs);
  t.set_mode(mode);
  t.mutable_displacement()->set_x_px(static_cast<int>(x_px));
  t.mutable_displacement()->set_x_subpx(static_cast<float>(x_px - static_cast<int>(x_px)));
  t.set_confidence(confidence);
  t.set_lock_lost(lock_lost);
  return t;
}

TEST(LockQuality, SmallResidualWithGoodConfidenceIsLocked) {
  LockQuality quality;
  for (int i = 0; i < 60; ++i) quality.add(Sample(i, (i % 2 == 0) ? 1.5 : -1.5));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kLocked);
  EXPECT_NEAR(quality.reading().rms_px, 1.5, 1e-6);
  EXPECT_NEAR(quality.reading().residual_px, 1.5, 1e-6);
}

TEST(LockQuality, ResidualRmsAboveFivePixelsIsDegraded) {
  LockQuality quality;
  for (int i = 0; i < 60; ++i) quality.add(Sample(i, (i % 2 == 0) ? 8 : -8));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kDegraded);
}

TEST(LockQuality, LowConfidenceIsDegraded) {
  LockQuality quality;
  for (int i = 0; i < 60; ++i) quality.add(Sample(i, 1, 0.1F));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kDegraded);
}

TEST(LockQuality, AgentsLockLostIsLost) {
  LockQuality quality;
  for (int i = 0; i < 30; ++i) quality.add(Sample(i, 1));
  quality.add(Sample(30, 1, 0.01F, /*lock_lost=*/true));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kLost);
}

// Issue 9: the agent's own word that it trails the view (a right match, lock held, the view
// beyond its off-target distance) turns an otherwise good reading to off target.
TEST(LockQuality, AgentsOffTargetIsDegradedAndSaid) {
  LockQuality quality;
  for (int i = 0; i < 30; ++i) quality.add(Sample(i, 1));
  ASSERT_EQ(quality.reading().verdict, LockVerdict::kLocked);
  kapfix::v1::Telemetry trailing = Sample(30, 1);
  trailing.set_off_target(true);
  quality.add(trailing);
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kDegraded);
  EXPECT_TRUE(quality.reading().off_target);
  quality.add(Sample(31, 1));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kLocked);
  EXPECT_FALSE(quality.reading().off_target);
}

TEST(LockQuality, ThirtyFivePixelResidualIsLostEvenWithoutTheAgentsFlag) {
  LockQuality quality;
  for (int i = 0; i < 60; ++i) quality.add(Sample(i, (i % 2 == 0) ? 35 : -35));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kLost);
}

TEST(LockQuality, RmsForgetsWhatIsOlderThanFiveSeconds) {
  LockQuality quality;
  for (int i = 0; i < 30; ++i) quality.add(Sample(i, 30));  // 1 s of a large residual
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kLost);
  for (int i = 30; i < 30 + 6 * 30; ++i) quality.add(Sample(i, 1));  // 6 s of a good lock
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kLocked);
  EXPECT_NEAR(quality.reading().rms_px, 1, 1e-6);
}

TEST(LockQuality, NotFixatingHasNoLockToJudge) {
  LockQuality quality;
  quality.add(Sample(0, 40, 0.0F, true, kapfix::v1::MODE_IDLE));
  EXPECT_EQ(quality.reading().verdict, LockVerdict::kNone);
}

TEST(LockQuality, OptionsRefuseThresholdsInTheWrongOrder) {
  LockQualityOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.lost_rms_px = 2;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("lost_rms_px"), std::string::npos);
}

TEST(LockQuality, SaysTheOnlineCalibrationAndTheForecastShare) {
  LockQuality quality;
  kapfix::v1::Telemetry t = Sample(0, 1.0);
  EXPECT_TRUE(quality.add(t).calibration.empty()) << "no estimate, nothing to say";
  t.mutable_deg_per_px()->set_pan_deg_per_px(0.105F);
  t.mutable_deg_per_px()->set_pan_uncertainty(0.03F);
  t.mutable_deg_per_px()->set_trusted(true);
  t.set_forecast_weight(0.8F);
  EXPECT_EQ(quality.add(t).calibration, "deg/px 0.1050 ±3 % trusted · forecast 80 %");
  t.mutable_deg_per_px()->set_trusted(false);
  t.mutable_deg_per_px()->set_pan_uncertainty(std::numeric_limits<float>::infinity());
  EXPECT_EQ(quality.add(t).calibration, "deg/px 0.1050 (no fit yet) · forecast 80 %");
}

}  // namespace
}  // namespace kapfix::station
