#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "agent/photos/agent_camera_trigger.hpp"
#include "agent/photos/photo_trigger.hpp"
#include "kapfix/v1/photo.pb.h"

namespace kapfix::agent {

// The cameras a photo can be taken with (issue 13): the agent's own, always there, and a
// still camera when the agent has one. The selected one takes each photo; when the still
// camera cannot (absent, busy, refusing, gone during the download), the agent's camera
// takes it from the same request's frame, and the metadata and a log line say why: a photo
// asked for is a photo stored. Thread-safe; Take runs on PhotoTaker's writer thread.
class PhotoCameras {
 public:
  void Select(kapfix::v1::PhotoCamera camera);  // UNSPECIFIED keeps the selection
  kapfix::v1::PhotoCamera selected() const;
  void SetStillCamera(std::shared_ptr<PhotoTrigger> still);

  // The photo of `request` by the selected camera, or by the agent's with
  // metadata->camera_fallback_reason set; fills metadata's camera, width, height and format.
  // Throws std::runtime_error when not even the agent's camera gives a photo.
  TakenPhoto Take(const PhotoRequest& request, kapfix::v1::PhotoMetadata* metadata);
  // `photo` (from Take) is stored: its camera may drop its own copy.
  void Stored(const TakenPhoto& photo);

 private:
  mutable std::mutex mutex_;
  kapfix::v1::PhotoCamera selected_ = kapfix::v1::PHOTO_CAMERA_AGENT;
  std::shared_ptr<PhotoTrigger> still_;
  AgentCameraTrigger agent_;  // stateless: used without the lock
};

}  // namespace kapfix::agent
