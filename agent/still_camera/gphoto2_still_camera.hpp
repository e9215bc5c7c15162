#pragma once

#include <memory>
#include <string>

#include "agent/still_camera/still_camera.hpp"

namespace kapfix::agent {

// A USB still camera through Debian's libgphoto2 (libgphoto2-dev): the first camera
// gp_camera_autodetect finds, in PTP or its maker's protocol. Only this file's .cpp
// includes the library's headers. In a build without libgphoto2
// (gphoto2_still_camera_stub.cpp) Open fails naming the missing library.
class Gphoto2StillCamera : public StillCamera {
 public:
  Gphoto2StillCamera();
  ~Gphoto2StillCamera() override;
  Gphoto2StillCamera(const Gphoto2StillCamera&) = delete;
  Gphoto2StillCamera& operator=(const Gphoto2StillCamera&) = delete;

  static bool Available();  // false in a build without libgphoto2

  bool Open(std::string* model, StillCameraError* error) override;
  void Close() override;
  bool Capture(std::string* camera_path, StillCameraError* error) override;
  bool Download(const std::string& camera_path, std::string* bytes, std::string* mime,
                StillCameraError* error) override;
  bool Delete(const std::string& camera_path, StillCameraError* error) override;
  std::string Name() const override { return "gphoto2"; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kapfix::agent
