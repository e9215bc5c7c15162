#include "agent/config/lens_profile.hpp"

#include <cmath>
#include <numbers>

#include "agent/config/options_from_settings.hpp"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

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
    return fail(
        "give either deg_per_px_pan and deg_per_px_tilt, or focal_length_mm and pixel_pitch_um");
  }
  if (direct) {
    if (!Positive(std::abs(deg_per_px_pan)) || !Positive(std::abs(deg_per_px_tilt)) ||
        std::abs(deg_per_px_pan) > 10 || std::abs(deg_per_px_tilt) > 10) {
      return fail("deg_per_px_pan and deg_per_px_tilt must both be non-zero with |deg/px| ≤ 10");
    }
    return true;
  }
  // The optics in the schema's ranges: the profile seen as its message (VisitFields).
  const std::string reason =
      kapfix::v1::CheckSettings(SettingsFromOptions<kapfix::v1::LensProfile>(*this), "");
  return reason.empty() || fail(reason);
}

void LensProfile::ApplyCalibration(const LensCalibration& calibration) {
  deg_per_px_pan = calibration.pan_deg_per_px;
  deg_per_px_tilt = calibration.tilt_deg_per_px;
  focal_mm = 0;
  pixel_pitch_um = 0;
}

double LensProfile::DegPerPxPan() const {
  return deg_per_px_pan != 0 ? deg_per_px_pan : FromFocal(focal_mm, pixel_pitch_um);
}

double LensProfile::DegPerPxTilt() const {
  return deg_per_px_tilt != 0 ? deg_per_px_tilt : FromFocal(focal_mm, pixel_pitch_um);
}

}  // namespace kapfix::agent
