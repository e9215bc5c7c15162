#include "agent/still_camera/fake_still_camera.hpp"

#include <utility>

namespace kapfix::agent {

FakeStillCamera::FakeStillCamera(std::string file, std::string model)
    : file_(std::move(file)), model_(std::move(model)) {}

void FakeStillCamera::Script(Behaviour behaviour) {
  std::lock_guard lock(mutex_);
  behaviour_ = behaviour;
  unplugged_ = false;
}

bool FakeStillCamera::Open(std::string* model, StillCameraError* error) {
  std::lock_guard lock(mutex_);
  ++opens_;
  if (behaviour_ == Behaviour::kAbsent || unplugged_) {
    *error = {StillCameraFault::kAbsent, "no camera found"};
    return false;
  }
  if (behaviour_ == Behaviour::kHeld) {
    *error = {StillCameraFault::kBusy, "opening: could not claim the USB device"};
    return false;
  }
  open_ = true;
  *model = model_;
  return true;
}

void FakeStillCamera::Close() {
  std::lock_guard lock(mutex_);
  open_ = false;
}

bool FakeStillCamera::Capture(std::string* camera_path, StillCameraError* error) {
  std::lock_guard lock(mutex_);
  if (!open_) {
    *error = {StillCameraFault::kAbsent, "capture: the camera is not open"};
    return false;
  }
  if (behaviour_ == Behaviour::kBusy) {
    *error = {StillCameraFault::kBusy, "capture: I/O in progress"};
    return false;
  }
  if (behaviour_ == Behaviour::kRefuses) {
    *error = {StillCameraFault::kRefused, "capture: unsupported operation"};
    return false;
  }
  ++captures_;
  *camera_path = "/store_00010001/DCIM/100FAKE/IMG_" + std::to_string(captures_) +
                 (behaviour_ == Behaviour::kGivesRaw ? ".CR2" : ".JPG");
  files_[*camera_path] = file_;
  return true;
}

bool FakeStillCamera::Download(const std::string& camera_path, std::string* bytes,
                               std::string* mime, StillCameraError* error) {
  std::lock_guard lock(mutex_);
  const auto it = files_.find(camera_path);
  if (!open_ || it == files_.end()) {
    *error = {StillCameraFault::kRefused, "download: file not found"};
    return false;
  }
  if (behaviour_ == Behaviour::kVanishesMidDownload) {
    *bytes = it->second.substr(0, it->second.size() / 2);  // what arrived before the cable went
    unplugged_ = true;
    open_ = false;
    *error = {StillCameraFault::kVanished, "download: I/O problem"};
    return false;
  }
  *bytes = it->second;
  *mime = behaviour_ == Behaviour::kGivesRaw ? "image/x-canon-cr2" : "image/jpeg";
  return true;
}

bool FakeStillCamera::Delete(const std::string& camera_path, StillCameraError* error) {
  std::lock_guard lock(mutex_);
  if (!open_ || files_.erase(camera_path) == 0) {
    *error = {StillCameraFault::kRefused, "delete: file not found"};
    return false;
  }
  return true;
}

int FakeStillCamera::opens() const {
  std::lock_guard lock(mutex_);
  return opens_;
}

int FakeStillCamera::captures() const {
  std::lock_guard lock(mutex_);
  return captures_;
}

bool FakeStillCamera::open() const {
  std::lock_guard lock(mutex_);
  return open_;
}

std::map<std::string, std::string> FakeStillCamera::files() const {
  std::lock_guard lock(mutex_);
  return files_;
}

}  // namespace kapfix::agent
