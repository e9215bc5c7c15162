#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "agent/photos/photo_trigger.hpp"
#include "agent/still_camera/still_camera.hpp"

namespace kapfix::agent {

// A still camera (USB, libgphoto2) as a PhotoTrigger: opened at the first photo, not at the
// agent's start (a camera switched on later is found); captures, downloads the file into
// memory and checks that it is a whole JPEG before handing it to the store, which writes it
// atomically, so a camera gone mid-download leaves nothing partial. After a fault that
// means the camera went away it is closed and detected again at the next photo. Only JPEG
// files are taken: a camera set to RAW is refused (the store names photos *.jpg).
class StillCameraTrigger : public PhotoTrigger {
 public:
  // `delete_on_camera`: delete the camera's copy once the photo is stored with its sidecar on
  // the agent (a long flight on a small card). Off: the camera's card keeps every photo too.
  explicit StillCameraTrigger(std::unique_ptr<StillCamera> camera, bool delete_on_camera = false);
  ~StillCameraTrigger() override;

  bool Take(const PhotoRequest& request, TakenPhoto* photo, std::string* error) override;
  void Stored(const TakenPhoto& photo) override;
  std::string Describe() const override;

  // The fault of the last failed Take (valid when it returned false).
  StillCameraFault last_fault() const;

 private:
  bool Fail(const StillCameraError& error, const std::string& context, std::string* out);

  mutable std::mutex mutex_;
  std::unique_ptr<StillCamera> camera_;
  bool delete_on_camera_ = false;
  bool open_ = false;
  std::string model_;
  StillCameraFault last_fault_ = StillCameraFault::kAbsent;
};

}  // namespace kapfix::agent
