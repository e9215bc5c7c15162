#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "kapfix/v1/settings.pb.h"

namespace kapfix::agent {

// What a camera is given to take one photo.
struct PhotoRequest {
  std::string file_name;  // the photo's name in the store (the take_photo reply named it);
                          // empty for an interval photo (the store names it)
  std::string note;
  // The agent camera's frame of the request (BGR), copied by the control thread: the
  // agent's own photo, and the fallback when another camera fails.
  cv::Mat agent_frame;
};

// One photo as it will be stored: the file's bytes, untouched.
struct TakenPhoto {
  std::string bytes;
  std::string format;  // "jpeg"
  std::uint32_t width_px = 0;
  std::uint32_t height_px = 0;
  kapfix::v1::PhotoCamera camera = kapfix::v1::PHOTO_CAMERA_UNSPECIFIED;
  // Where the camera keeps its own copy (a still camera's "/store_00010001/DCIM/IMG_0001.JPG");
  // empty when it keeps none.
  std::string camera_path;
};

// The camera that takes a photo (issue 13): the agent's own, or a still camera. Called by
// PhotoTaker's writer thread, never by the control thread: a still camera's capture and
// download take seconds.
class PhotoTrigger {
 public:
  virtual ~PhotoTrigger() = default;

  // Takes the photo and gives its bytes; nothing is written to disk here (the store does
  // that, atomically). False with a one-line reason when there is no photo.
  virtual bool Take(const PhotoRequest& request, TakenPhoto* photo, std::string* error) = 0;
  // `photo` is now stored with its sidecar: a camera may drop its own copy.
  virtual void Stored(const TakenPhoto& /*photo*/) {}
  virtual std::string Describe() const = 0;
};

}  // namespace kapfix::agent
