#pragma once

#include <functional>
#include <string>
#include <vector>

#include "kapfix/v1/settings.pb.h"

namespace kapfix::agent {

// How one camera backend applies the camera settings message (kapfix.v1.CameraSettings): one
// control per field the camera has, found by field number. A field the backend has no
// control for is refused by its name, so a setting added to the message reaches every
// backend without a change to the FrameSource interface: the ones that do not know it say so.
class CameraSettingControls {
 public:
  // Sets the camera to `value` (a bool field arrives as 0 or 1) in the field's unit; false +
  // a short reason ("outside its range [0, 24] dB") when the camera refuses.
  using Control = std::function<bool(double value, std::string* reason)>;

  // `field_number`: kapfix::v1::CameraSettings::k…FieldNumber.
  CameraSettingControls& Add(int field_number, Control control);

  // Applies every field set in `settings` through its control, in field order; a field left
  // unset leaves the camera's own. A field that fails, or that has no control, does not stop
  // the others: all of them are named in one line, "CAMERA: gain_db = 60 dB: outside its
  // range [0, 24] dB; exposure_us = 2000 µs: this camera has no such control".
  bool Apply(const kapfix::v1::CameraSettings& settings, const std::string& camera,
             std::string* error) const;

 private:
  struct Entry {
    int field_number;
    Control control;
  };
  std::vector<Entry> controls_;
};

}  // namespace kapfix::agent
