#include "agent/config/lens_profile.hpp"

#include <cmath>
#include <numbers>

namespace kapfix::agent {
namespace {

bool Positive(double v) { return std::isfinite(v) && v > 0; }

double FromFocal(double focal_mm, double pixel_pitch_um) {
  return std::atan(pixel_pitch_um * 1e-3 / focal_mm) * 180.0 / std::numbers::pi;
}

}  // namespace

bool LensProfile::IsValid(std::string* error) const {
  auto fail = [error, this](const std::string& message) {
    if (error) *error = "lens '" + name + "': " + message;
    return false;
  };
  if (name.empty()) {
    if (error) *error = "lens: name is empty";
    return false;
  }
  const bool direct = deg_per_px_pan != 0 || deg_per_px_tilt != 0;
  const bool optical = focal_mm != 0 || pixel_pitch_um != 0;
  if (direct == optical) {
    return fail("give either deg_per_px_pan and deg_per_px_tilt, or focal_mm and pixel_pitch_um");
  }
  if (direct) {
    if (!Positive(deg_per_px_pan) || !Positive(deg_per_px_tilt) || deg_per_px_pan > 10 ||
        deg_per_px_tilt > 10) {
      return fail("deg_per_px_pan and deg_per_px_tilt must both be in (0, 10] deg/px");
    }
    return true;
  }
  if (!Positive(focal_mm) || focal_mm < 0.5 || focal_mm > 500) {
    return fail("focal_mm must be 0.5…500 mm, got " + std::to_string(focal_mm));
  }
  if (!Positive(pixel_pitch_um) || pixel_pitch_um < 0.5 || pixel_pitch_um > 200) {
    return fail("pixel_pitch_um must be 0.5…200 µm, got " + std::to_string(pixel_pitch_um));
  }
  return true;
}

double LensProfile::DegPerPxPan() const {
  return deg_per_px_pan != 0 ? deg_per_px_pan : FromFocal(focal_mm, pixel_pitch_um);
}

double LensProfile::DegPerPxTilt() const {
  return deg_per_px_tilt != 0 ? deg_per_px_tilt : FromFocal(focal_mm, pixel_pitch_um);
}

}  // namespace kapfix::agent
