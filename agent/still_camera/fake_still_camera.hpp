#pragma once

#include <map>
#include <mutex>
#include <string>

#include "agent/still_camera/still_camera.hpp"

namespace kapfix::agent {

// A scriptable still camera for tests: each capture "takes" the file it was given (e.g. a
// real JPEG's bytes) and keeps it under a new path until deleted. Thread-safe, so a test can
// script it while a writer thread uses it.
class FakeStillCamera : public StillCamera {
 public:
  enum class Behaviour {
    kSucceeds,
    kAbsent,               // Open finds no camera
    kHeld,                 // Open: another program holds the camera (busy)
    kBusy,                 // Capture: the camera is busy
    kRefuses,              // Capture: the camera will not capture (e.g. not in PTP mode)
    kVanishesMidDownload,  // Download gives half the file, then fails; unplugged after
    kGivesRaw,             // the file is a RAW (MIME image/x-canon-cr2)
  };

  FakeStillCamera(std::string file, std::string model = "Fake EOS on usb:001,002");

  void Script(Behaviour behaviour);

  bool Open(std::string* model, StillCameraError* error) override;
  void Close() override;
  bool Capture(std::string* camera_path, StillCameraError* error) override;
  bool Download(const std::string& camera_path, std::string* bytes, std::string* mime,
                StillCameraError* error) override;
  bool Delete(const std::string& camera_path, StillCameraError* error) override;
  std::string Name() const override { return "fake"; }

  int opens() const;
  int captures() const;
  bool open() const;
  std::map<std::string, std::string> files() const;  // on the camera, by path

 private:
  mutable std::mutex mutex_;
  std::string file_;
  std::string model_;
  Behaviour behaviour_ = Behaviour::kSucceeds;
  bool open_ = false;
  bool unplugged_ = false;  // after a vanish, until scripted again
  int opens_ = 0;
  int captures_ = 0;
  std::map<std::string, std::string> files_;
};

}  // namespace kapfix::agent
