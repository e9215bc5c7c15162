#include "common/control/lens_calibration.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace kapfix {
namespace {

TEST(LensCalibrationTest, CalibrationMovesGiveTheNegatedFit) {
  // A move of +1° showed the content 10 px to the left: the move that corrects +10 px is +1°.
  AxisCalibration pan;
  pan.units_per_px_fit = -0.1;
  AxisCalibration tilt;
  tilt.units_per_px_fit = 0.05;  // a tilt servo mounted the other way round
  const LensCalibration c = LensCalibration::FromCalibrationMoves(pan, tilt);
  EXPECT_DOUBLE_EQ(c.pan_deg_per_px, 0.1);
  EXPECT_DOUBLE_EQ(c.tilt_deg_per_px, -0.05);
}

TEST(LensCalibrationTest, RejectsZeroOrNonFiniteGains) {
  std::string error;
  EXPECT_TRUE((LensCalibration{0.1, -0.1}.IsValid(&error)));
  EXPECT_FALSE((LensCalibration{0.0, 0.1}.IsValid(&error)));
  EXPECT_NE(error.find("non-zero"), std::string::npos);
  EXPECT_FALSE((LensCalibration{0.1, std::numeric_limits<double>::infinity()}.IsValid(nullptr)));
}

}  // namespace
}  // namespace kapfix
