#pragma once

#include <string>

#include "common/control/calibration.hpp"

namespace kapfix {

// The controller's axis calibration (SPEC §2.7): degrees of servo that correct one pixel of
// measured displacement. With the sign chain of SimulatedPlatform (and of a rig whose servo
// turns the view the way its angle grows) both are positive: a positive displacement is
// corrected by a positive command, target = angle + displacement · deg_per_px.
struct LensCalibration {
  double pan_deg_per_px = 0.1;   // [deg/px] along x
  double tilt_deg_per_px = 0.1;  // [deg/px] along y

  // Finite and non-zero on both axes (a negative value is a servo mounted the other way).
  bool IsValid(std::string* error) const;

  // From thesis-style calibrations (CalibrateAxis over moves in degrees): those measure the
  // displacement a move *causes*, which is the opposite of the displacement that move
  // corrects, so the correcting gain is −units_per_px_fit (the robust line fit, which
  // absorbs a constant offset in the displacements).
  static LensCalibration FromCalibrationMoves(const AxisCalibration& pan,
                                              const AxisCalibration& tilt);
};

}  // namespace kapfix
