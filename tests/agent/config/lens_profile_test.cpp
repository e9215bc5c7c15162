#include "agent/config/lens_profile.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

TEST(LensProfileTest, GivenDegreesPerPixelAreUsedAsTheyAre) {
  const LensProfile lens{.name = "a", .deg_per_px_pan = 0.2, .deg_per_px_tilt = 0.3};
  EXPECT_EQ(lens.DegPerPxPan(), 0.2);
  EXPECT_EQ(lens.DegPerPxTilt(), 0.3);
}

TEST(LensProfileTest, FocalLengthAndPitchGiveTheAngleOfOnePixel) {
  // atan(5 µm / 3.5 mm) = 0.08185 deg.
  const LensProfile lens{.name = "3.5mm", .focal_mm = 3.5, .pixel_pitch_um = 5};
  EXPECT_NEAR(lens.DegPerPxPan(), 0.081851, 1e-6);
  EXPECT_EQ(lens.DegPerPxPan(), lens.DegPerPxTilt());
}

TEST(LensProfileTest, BothFormsAtOnceAreInvalid) {
  const LensProfile lens{.name = "x",
                         .deg_per_px_pan = 0.1,
                         .deg_per_px_tilt = 0.1,
                         .focal_mm = 6,
                         .pixel_pitch_um = 5};
  std::string error;
  EXPECT_FALSE(lens.IsValid(&error));
  EXPECT_NE(error.find("either"), std::string::npos) << error;
}

TEST(LensProfileTest, NeitherFormIsInvalid) {
  EXPECT_FALSE(LensProfile{.name = "x"}.IsValid(nullptr));
}

TEST(LensProfileTest, FocalLengthWithoutPitchIsInvalid) {
  EXPECT_FALSE((LensProfile{.name = "x", .focal_mm = 6}).IsValid(nullptr));
}

TEST(LensProfileTest, UnnamedProfileIsInvalid) {
  LensProfile lens;
  lens.deg_per_px_pan = 0.1;
  lens.deg_per_px_tilt = 0.1;
  EXPECT_FALSE(lens.IsValid(nullptr));
}

TEST(LensProfileTest, ACalibrationAppliedToAnOpticalProfileLeavesAValidProfile) {
  // resources/kite.json defines its lens by its optics; a calibration must replace them.
  LensProfile lens{.name = "3.5mm", .focal_mm = 3.5, .pixel_pitch_um = 5};
  lens.ApplyCalibration(LensCalibration{.pan_deg_per_px = 0.07, .tilt_deg_per_px = 0.09});
  std::string error;
  EXPECT_TRUE(lens.IsValid(&error)) << error;
  EXPECT_EQ(lens.DegPerPxPan(), 0.07);
  EXPECT_EQ(lens.DegPerPxTilt(), 0.09);
}

TEST(LensProfileTest, ACalibrationOfAReversedServoIsAValidProfile) {
  // LensCalibration::IsValid accepts a negative slope (a servo mounted the other way).
  LensProfile lens{.name = "6mm", .deg_per_px_pan = 0.1, .deg_per_px_tilt = 0.1};
  lens.ApplyCalibration(LensCalibration{.pan_deg_per_px = -0.05, .tilt_deg_per_px = 0.05});
  std::string error;
  EXPECT_TRUE(lens.IsValid(&error)) << error;
}

}  // namespace
}  // namespace kapfix::agent
