#include "agent/preflight/preflight.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "agent/agent.hpp"
#include "agent/preflight/still_camera_check.hpp"
#include "agent/still_camera/gphoto2_still_camera.hpp"
#include "link/curve_key_file.hpp"

namespace kapfix::agent {
namespace {

namespace fs = std::filesystem;

PreflightCheck Pass(std::string what, std::string detail) {
  return {.pass = true, .what = std::move(what), .detail = std::move(detail), .fix = ""};
}

PreflightCheck Failed(std::string what, std::string detail, std::string fix) {
  return {
      .pass = false, .what = std::move(what), .detail = std::move(detail), .fix = std::move(fix)};
}

PreflightCheck CheckSecretKey(const std::string& path) {
  const std::string what = "agent key " + path;
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    return Failed(what, "missing",
                  "kapfix-keygen agent --dir " + fs::path(path).parent_path().string() +
                      " && chown kapfix:kapfix " + path + " (the package's postinst does this)");
  }
  if ((info.st_mode & 077) != 0) {
    return Failed(what, "readable by others (mode " + std::to_string(info.st_mode & 0777) + ")",
                  "chmod 600 " + path);
  }
  if (::access(path.c_str(), R_OK) != 0) {
    return Failed(what, "not readable by this user",
                  "chown kapfix:kapfix " + path + " (the service runs as user kapfix)");
  }
  std::string why;
  if (!kapfix::link::ReadSecretKeyFile(path, &why)) return Failed(what, why, "regenerate it");
  return Pass(what, "present, mode 0600, readable");
}

PreflightCheck CheckAuthorizedKeys(const std::string& path) {
  const std::string what = "station keys " + path;
  std::string why;
  const auto stations = kapfix::link::ReadPublicKeyLines(path, &why);
  if (!stations) {
    return Failed(what, why, "create it (empty is fine): install -m 0644 /dev/null " + path);
  }
  if (stations->empty()) {
    return Pass(what,
                "no station yet: the agent serves 127.0.0.1 only until a station's .pub "
                "line is appended");
  }
  return Pass(what, std::to_string(stations->size()) + " station key(s)");
}

PreflightCheck CheckCamera(const CameraConfig& camera) {
  auto source = MakeCamera(camera);
  std::string error;
  if (!source->Open(&error)) {
    return Failed("camera", error,
                  "check the cable and power, `--camera SPEC` to try another device, and the "
                  "user's groups (video, plugdev)");
  }
  // The configured settings, as the agent applies them; one the camera refuses is said but
  // does not fail the check (the agent flies with the camera's own, as it would then).
  std::string refused;
  if (!source->Apply(camera.settings, &refused)) refused = "; settings not all applied: " + refused;
  CapturedFrame frame;
  if (!source->Grab(&frame, &error)) {
    return Failed("camera", source->Describe() + " opened but gave no frame: " + error,
                  "check the camera's trigger mode and, for GigE, the network and MTU");
  }
  return Pass("camera", source->Describe() + ", one " + std::to_string(frame.image.cols) + "x" +
                            std::to_string(frame.image.rows) + " frame" + refused);
}

PreflightCheck CheckServos(const ServoConfig& servo) {
  auto backend = MakeServoBackend(servo);
  std::string error;
  if (!backend->Open(&error)) {
    return Failed("servos", error,
                  "check the controller's cable and power, `--servos SPEC`, and the user's groups "
                  "(dialout, plugdev, i2c)");
  }
  return Pass("servos", backend->Describe() + " opened and answered (nothing moved)");
}

PreflightCheck CheckPhotoFolder(const std::string& dir, std::uintmax_t min_free) {
  const std::string what = "photo folder " + dir;
  std::error_code code;
  fs::path existing = fs::absolute(dir, code);
  while (!existing.empty() && !fs::exists(existing, code)) existing = existing.parent_path();
  if (existing.empty() || ::access(existing.c_str(), W_OK) != 0) {
    return Failed(what, "not writable (" + existing.string() + ")",
                  "create it owned by the agent's user, or set photos.dir / --photos");
  }
  const fs::space_info space = fs::space(existing, code);
  if (code) return Failed(what, "free space unknown: " + code.message(), "check the mount");
  const auto mib = [](std::uintmax_t bytes) { return std::to_string(bytes >> 20) + " MiB"; };
  if (space.available < min_free) {
    return Failed(what, "only " + mib(space.available) + " free (need " + mib(min_free) + ")",
                  "free space or point photos.dir at a larger card");
  }
  return Pass(what, mib(space.available) + " free");
}

PreflightCheck CheckClock() {
  const auto now = std::chrono::system_clock::now();
  const auto year = std::chrono::year_month_day(std::chrono::floor<std::chrono::days>(now)).year();
  if (year < std::chrono::year(2024)) {
    return Failed("clock", "the date is in " + std::to_string(static_cast<int>(year)),
                  "no real-time clock and no network time: photos would be misdated; enable "
                  "systemd-timesyncd or set the date (date -s)");
  }
  const bool synced = fs::exists("/run/systemd/timesync/synchronized");
  return Pass("clock", std::string("date plausible") +
                           (synced ? ", synchronised by systemd-timesyncd" : ""));
}

}  // namespace

std::string PreflightCheck::Line() const {
  std::string line = (pass ? "PASS " : "FAIL ") + what + ": " + detail;
  if (!pass && !fix.empty()) line += "; fix: " + fix;
  return line;
}

std::vector<PreflightCheck> RunPreflight(const AgentConfig& config,
                                         const PreflightOptions& options) {
  std::vector<PreflightCheck> checks;
  std::string error;
  if (!config.IsValid(&error)) {
    checks.push_back(Failed("configuration", error, "edit the configuration file"));
    return checks;  // the other checks read the config
  }
  checks.push_back(Pass("configuration", "valid"));
  if (!config.link.curve_secret_key_file.empty()) {
    checks.push_back(CheckSecretKey(config.link.curve_secret_key_file));
    checks.push_back(CheckAuthorizedKeys(config.link.curve_authorized_keys_file));
  }
  const bool simulated = options.simulate || (config.camera.backend == CameraBackend::kSim &&
                                              config.servo.backend == ServoBackend::kSim);
  if (simulated) {
    const bool scene = !cv::imread(config.simulation.scene, cv::IMREAD_REDUCED_COLOR_8).empty();
    checks.push_back(scene ? Pass("simulation", "scene " + config.simulation.scene)
                           : Failed("simulation", "cannot read scene " + config.simulation.scene,
                                    "install opencv-doc or pass --scene PHOTO"));
  } else {
    checks.push_back(config.camera.backend == CameraBackend::kSim
                         ? Failed("camera", "sim with real servos", "--camera SPEC or --sim")
                         : CheckCamera(config.camera));
    checks.push_back(config.servo.backend == ServoBackend::kSim
                         ? Failed("servos", "sim with a real camera", "--servos SPEC or --sim")
                         : CheckServos(config.servo));
  }
  if (options.photo_camera == kapfix::v1::PHOTO_CAMERA_GPHOTO2) {
    Gphoto2StillCamera still;
    checks.push_back(CheckStillCamera(still));
  }
  checks.push_back(CheckPhotoFolder(config.photos.dir, options.min_free_bytes));
  checks.push_back(CheckClock());
  return checks;
}

}  // namespace kapfix::agent
