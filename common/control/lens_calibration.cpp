#include "common/control/lens_calibration.hpp"

#include <cmath>

namespace kapfix {

bool LensCalibration::IsValid(std::string* error) const {
  for (const double v : {pan_deg_per_px, tilt_deg_per_px}) {
    if (!std::isfinite(v) || v == 0.0) {
      if (error)
        *error = "lens calibration must be finite and non-zero deg/px, got " + std::to_string(v);
      return false;
    }
  }
  return true;
}

LensCalibration LensCalibration::FromCalibrationMoves(const AxisCalibration& pan,
                                                      const AxisCalibration& tilt) {
  return {-pan.units_per_px_fit, -tilt.units_per_px_fit};
}

}  // namespace kapfix
