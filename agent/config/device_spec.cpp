#include "agent/config/device_spec.hpp"

#include <charconv>

namespace kapfix::agent {
namespace {

constexpr std::string_view kCameraForms = "sim, v4l2:/dev/videoN, v4l2:N, aravis or aravis:ID";
constexpr std::string_view kServoForms =
    "sim, maestro:/dev/ttyACMn, pca9685:/dev/i2c-N or pca9685:/dev/i2c-N@0xAA";

bool Fail(std::string_view flag, std::string_view spec, const std::string& why,
          std::string_view forms, std::string* error) {
  if (error) {
    *error = std::string(flag) + " \"" + std::string(spec) + "\": " + why + "; use " +
             std::string(forms);
  }
  return false;
}

// "maestro:/dev/x" → {"maestro", "/dev/x", true}; "sim" → {"sim", "", false}.
struct Split {
  std::string_view backend;
  std::string_view device;
  bool has_device = false;
};

Split SplitSpec(std::string_view spec) {
  const auto colon = spec.find(':');
  if (colon == std::string_view::npos) return {spec, {}, false};
  return {spec.substr(0, colon), spec.substr(colon + 1), true};
}

}  // namespace

bool ApplyCameraSpec(std::string_view spec, CameraConfig* camera, std::string* error) {
  constexpr std::string_view kFlag = "--camera";
  const Split s = SplitSpec(spec);
  if (s.backend == "sim") {
    if (s.has_device) return Fail(kFlag, spec, "sim takes no device", kCameraForms, error);
    camera->backend = CameraBackend::kSim;
    camera->device.clear();
    return true;
  }
  if (s.backend == "v4l2") {
    if (s.device.empty()) return Fail(kFlag, spec, "v4l2 needs a device", kCameraForms, error);
    camera->backend = CameraBackend::kV4l2;
    camera->device = std::string(s.device);
    return true;
  }
  if (s.backend == "aravis") {
    if (s.has_device && s.device.empty()) {
      return Fail(kFlag, spec, "empty camera id after \"aravis:\"", kCameraForms, error);
    }
    camera->backend = CameraBackend::kAravis;
    camera->device = std::string(s.device);  // "" = the first camera Aravis finds
    return true;
  }
  return Fail(kFlag, spec, "unknown camera backend \"" + std::string(s.backend) + "\"",
              kCameraForms, error);
}

bool ApplyServoSpec(std::string_view spec, ServoConfig* servo, std::string* error) {
  constexpr std::string_view kFlag = "--servos";
  const Split s = SplitSpec(spec);
  if (s.backend == "sim") {
    if (s.has_device) return Fail(kFlag, spec, "sim takes no device", kServoForms, error);
    servo->backend = ServoBackend::kSim;
    servo->device.clear();
    return true;
  }
  if (s.backend == "maestro") {
    if (s.device.empty()) return Fail(kFlag, spec, "maestro needs a device", kServoForms, error);
    servo->backend = ServoBackend::kMaestro;
    servo->device = std::string(s.device);
    return true;
  }
  if (s.backend == "pca9685") {
    std::string_view device = s.device;
    int address = servo->i2c_address;
    if (const auto at = device.find('@'); at != std::string_view::npos) {
      std::string_view text = device.substr(at + 1);
      device = device.substr(0, at);
      int base = 10;
      if (text.starts_with("0x") || text.starts_with("0X")) {
        text.remove_prefix(2);
        base = 16;
      }
      const auto [end, code] =
          std::from_chars(text.data(), text.data() + text.size(), address, base);
      if (text.empty() || code != std::errc() || end != text.data() + text.size() ||
          address < 0x03 || address > 0x77) {
        return Fail(kFlag, spec, "I2C address must be 0x03…0x77", kServoForms, error);
      }
    }
    if (device.empty()) return Fail(kFlag, spec, "pca9685 needs a device", kServoForms, error);
    servo->backend = ServoBackend::kPca9685;
    servo->device = std::string(device);
    servo->i2c_address = address;
    return true;
  }
  return Fail(kFlag, spec, "unknown servo backend \"" + std::string(s.backend) + "\"", kServoForms,
              error);
}

}  // namespace kapfix::agent
