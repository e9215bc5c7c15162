// The gphoto2 still camera of a build without libgphoto2 (pkg-config did not find
// libgphoto2-dev): every call fails with that reason, so selecting the still camera gives a
// clear fallback reason rather than a link error.
#include "agent/still_camera/gphoto2_still_camera.hpp"

namespace kapfix::agent {

struct Gphoto2StillCamera::Impl {};

namespace {

bool BuiltWithout(StillCameraError* error) {
  if (error) {
    *error = {StillCameraFault::kAbsent,
              "kapfix was built without libgphoto2 (install libgphoto2-dev, then configure "
              "again)"};
  }
  return false;
}

}  // namespace

Gphoto2StillCamera::Gphoto2StillCamera() : impl_(std::make_unique<Impl>()) {}
Gphoto2StillCamera::~Gphoto2StillCamera() = default;

bool Gphoto2StillCamera::Available() { return false; }

bool Gphoto2StillCamera::Open(std::string* /*model*/, StillCameraError* error) {
  return BuiltWithout(error);
}
void Gphoto2StillCamera::Close() {}
bool Gphoto2StillCamera::Capture(std::string* /*camera_path*/, StillCameraError* error) {
  return BuiltWithout(error);
}
bool Gphoto2StillCamera::Download(const std::string& /*camera_path*/, std::string* /*bytes*/,
                                  std::string* /*mime*/, StillCameraError* error) {
  return BuiltWithout(error);
}
bool Gphoto2StillCamera::Delete(const std::string& /*camera_path*/, StillCameraError* error) {
  return BuiltWithout(error);
}

}  // namespace kapfix::agent
