#include "groundstation/photos/photo_quality.hpp"

#include <gtest/gtest.h>

namespace kapfix::station {
namespace {

kapfix::v1::PhotoMetadata Measured(float blur_px, float offset_px) {
  kapfix::v1::PhotoMetadata m;
  m.set_shutter(kapfix::v1::SHUTTER_INTERVAL);
  m.set_view_blur_px(blur_px);
  m.set_residual_offset_px(offset_px);
  return m;
}

TEST(PhotoQuality, BlurredIsMoreThanOnePixelOfTravelDuringTheExposure) {
  EXPECT_FALSE(JudgePhoto(Measured(static_cast<float>(kBlurredPx), 0)).blurred);
  EXPECT_TRUE(JudgePhoto(Measured(static_cast<float>(kBlurredPx) + 0.1F, 0)).blurred);
}

TEST(PhotoQuality, OffTargetIsFartherThanTheThresholdOrALostLock) {
  EXPECT_FALSE(JudgePhoto(Measured(0, static_cast<float>(kOffTargetPx))).off_target);
  EXPECT_TRUE(JudgePhoto(Measured(0, static_cast<float>(kOffTargetPx) + 0.5F)).off_target);
  kapfix::v1::PhotoMetadata lost = Measured(0, 0);
  lost.set_lock_lost(true);
  EXPECT_TRUE(JudgePhoto(lost).off_target);
}

TEST(PhotoQuality, BothFlagsAreNamedWithTheirFigures) {
  const PhotoJudgement judgement = JudgePhoto(Measured(1.8F, 12));
  EXPECT_EQ(judgement.flags,
            "BLURRED (1.8 px during the exposure), OFF TARGET (12.0 px from the reference)");
}

TEST(PhotoQuality, APhotoWithoutQualityFiguresIsNotJudged) {
  kapfix::v1::PhotoMetadata old;
  old.set_lock_lost(true);  // not read: an older agent measured nothing
  const PhotoJudgement judgement = JudgePhoto(old);
  EXPECT_FALSE(judgement.measured);
  EXPECT_TRUE(judgement.flags.empty());
}

}  // namespace
}  // namespace kapfix::station
