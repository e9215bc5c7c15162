#pragma once

#include <string>
#include <string_view>

namespace kapfix::agent {

// Why a still camera gave no photo: what the operator can do differs.
enum class StillCameraFault {
  kAbsent,    // no camera detected: cable, power, USB mode
  kBusy,      // another program holds it, or it is still busy with the last photo
  kRefused,   // it answered but will not capture or give the file (mode, settings, model)
  kVanished,  // it went away during capture or download (cable, battery)
};

std::string_view ToString(StillCameraFault fault);

struct StillCameraError {
  StillCameraFault fault = StillCameraFault::kAbsent;
  std::string message;  // one line, without the camera's name
};

// The few calls of a still camera library that a photo needs (libgphoto2: Gphoto2StillCamera;
// tests: FakeStillCamera). Not thread-safe: one thread at a time. A file on the camera is
// named by its path there, "/store_00010001/DCIM/100CANON/IMG_0001.JPG".
class StillCamera {
 public:
  virtual ~StillCamera() = default;

  // Finds the first camera and opens it; `model` names it ("Canon EOS 600D on usb:001,005").
  virtual bool Open(std::string* model, StillCameraError* error) = 0;
  virtual void Close() = 0;
  // Takes one photo, which the camera keeps; gives its path there.
  virtual bool Capture(std::string* camera_path, StillCameraError* error) = 0;
  // The file's bytes and MIME type ("image/jpeg"). On failure `bytes` may hold part of the
  // file: the caller keeps none of it.
  virtual bool Download(const std::string& camera_path, std::string* bytes, std::string* mime,
                        StillCameraError* error) = 0;
  virtual bool Delete(const std::string& camera_path, StillCameraError* error) = 0;
  virtual std::string Name() const = 0;  // "gphoto2": the reasons start with it
};

}  // namespace kapfix::agent
