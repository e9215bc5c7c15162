#pragma once

#include <string>

#include "common/control/lens_calibration.hpp"

namespace kapfix::agent {

// How far the view turns per pixel, per axis, for one lens (SPEC §2.7: calibration is stored
// per lens profile; the thesis compared 3.5 mm and 6 mm lenses). Given either directly, or as
// focal length and pixel pitch — the pitch of the frame's pixels as captured, i.e. the sensor
// pitch times any binning or downscaling between sensor and frame.
struct LensProfile {
  std::string name;
  double deg_per_px_pan = 0;   // [deg/px] 0 = derive from the focal length and pixel pitch
  double deg_per_px_tilt = 0;  // [deg/px]
  double focal_mm = 0;         // [mm]
  double pixel_pitch_um = 0;   // [µm] per frame pixel

  // A name, and exactly one of the two forms with finite values: deg/px non-zero with
  // |deg/px| ≤ 10 (negative: a servo mounted the other way, as a calibration can measure),
  // or focal length and pitch in the schema's ranges (kapfix.v1.LensProfile).
  bool IsValid(std::string* error) const;

  // The one way a measured calibration enters a profile (at start-up from the calibration
  // store, and when a calibration run finishes): its deg/px replace what the optics said, and
  // the optics are cleared, since a profile holds one form or the other (IsValid).
  void ApplyCalibration(const LensCalibration& calibration);

  // [deg/px] given, or the angle one pixel subtends at the optical centre:
  // atan(pitch / focal) (same for both axes: square pixels).
  double DegPerPxPan() const;
  double DegPerPxTilt() const;

  // The members a settings command sets, by the names of their settings (kapfix.v1.LensProfile);
  // deg/px are measured (ApplyCalibration), not set.
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("name", name);
    visit("focal_length_mm", focal_mm);
    visit("pixel_pitch_um", pixel_pitch_um);
  }
};

}  // namespace kapfix::agent
