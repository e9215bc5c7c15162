#pragma once

#include <string>

namespace kapfix::agent {

// How far the view turns per pixel, per axis, for one lens (SPEC §2.7: calibration is stored
// per lens profile; the thesis compared 3.5 mm and 6 mm lenses). Given either directly, or as
// focal length and pixel pitch — the pitch of the frame's pixels as captured, i.e. the sensor
// pitch times any binning or downscaling between sensor and frame.
struct LensProfile {
  std::string name;
  double deg_per_px_pan = 0;   // [deg/px] 0 = derive from focal_mm and pixel_pitch_um
  double deg_per_px_tilt = 0;  // [deg/px]
  double focal_mm = 0;         // [mm]
  double pixel_pitch_um = 0;   // [µm] per frame pixel

  // A name, and exactly one of the two forms with positive, finite values (deg_per_px ≤ 10,
  // focal 0.5…500 mm, pitch 0.5…200 µm).
  bool IsValid(std::string* error) const;

  // [deg/px] given, or the angle one pixel subtends at the optical centre:
  // atan(pitch / focal) (same for both axes: square pixels).
  double DegPerPxPan() const;
  double DegPerPxTilt() const;
};

}  // namespace kapfix::agent
