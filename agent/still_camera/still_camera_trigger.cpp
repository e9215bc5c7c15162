#include "agent/still_camera/still_camera_trigger.hpp"

#include <spdlog/spdlog.h>

#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace kapfix::agent {
namespace {

// A JPEG ends with the EOI marker (FF D9), possibly followed by zero padding. libjpeg decodes
// a truncated file without failing (the missing rows are grey), so the end is checked too.
bool EndsLikeAJpeg(const std::string& bytes) {
  std::size_t end = bytes.size();
  while (end > 0 && bytes[end - 1] == '\0') --end;
  return end >= 2 && static_cast<unsigned char>(bytes[end - 2]) == 0xFF &&
         static_cast<unsigned char>(bytes[end - 1]) == 0xD9;
}

}  // namespace

StillCameraTrigger::StillCameraTrigger(std::unique_ptr<StillCamera> camera, bool delete_on_camera)
    : camera_(std::move(camera)), delete_on_camera_(delete_on_camera) {}

StillCameraTrigger::~StillCameraTrigger() {
  if (open_) camera_->Close();
}

bool StillCameraTrigger::Fail(const StillCameraError& error, const std::string& context,
                              std::string* out) {
  last_fault_ = error.fault;
  // Gone or never there: detect it again at the next photo (it may be another camera by then).
  if (open_ &&
      (error.fault == StillCameraFault::kAbsent || error.fault == StillCameraFault::kVanished)) {
    camera_->Close();
    open_ = false;
  }
  if (out) *out = camera_->Name() + ": " + error.message + context;
  return false;
}

bool StillCameraTrigger::Take(const PhotoRequest& /*request*/, TakenPhoto* photo,
                              std::string* error) {
  std::lock_guard lock(mutex_);
  StillCameraError fault;
  if (!open_) {
    if (!camera_->Open(&model_, &fault)) return Fail(fault, "", error);
    open_ = true;
    spdlog::info("still camera: {} ({})", model_, camera_->Name());
  }
  std::string path;
  if (!camera_->Capture(&path, &fault)) return Fail(fault, "", error);
  // From here on the camera holds the photo: every reason says where, so it is not lost.
  const std::string kept = " (the photo stays on the camera as " + path + ")";
  std::string bytes;
  std::string mime;
  if (!camera_->Download(path, &bytes, &mime, &fault)) return Fail(fault, kept, error);
  if (mime != "image/jpeg") {
    return Fail({StillCameraFault::kRefused,
                 "the camera gave a " + (mime.empty() ? std::string("file of no type") : mime) +
                     " file, not a JPEG: set its image quality to JPEG"},
                kept, error);
  }
  // A whole JPEG, not a truncated one: decoding also gives the size for the sidecar. [s] on
  // the writer thread, which can wait.
  const cv::Mat image =
      EndsLikeAJpeg(bytes)
          ? cv::imdecode(std::vector<unsigned char>(bytes.begin(), bytes.end()), cv::IMREAD_COLOR)
          : cv::Mat();
  if (image.empty()) {
    return Fail(
        {StillCameraFault::kVanished,
         "the downloaded file (" + std::to_string(bytes.size()) + " bytes) is not a whole JPEG"},
        kept, error);
  }
  photo->bytes = std::move(bytes);
  photo->format = "jpeg";
  photo->width_px = static_cast<std::uint32_t>(image.cols);
  photo->height_px = static_cast<std::uint32_t>(image.rows);
  photo->camera = kapfix::v1::PHOTO_CAMERA_GPHOTO2;
  photo->camera_path = path;
  return true;
}

void StillCameraTrigger::Stored(const TakenPhoto& photo) {
  if (!delete_on_camera_ || photo.camera_path.empty()) return;
  std::lock_guard lock(mutex_);
  StillCameraError fault;
  if (!open_ || !camera_->Delete(photo.camera_path, &fault)) {
    // Harmless: the photo is stored on the agent and also stays on the camera's card.
    spdlog::warn("still camera: {} not deleted on the camera: {}", photo.camera_path,
                 open_ ? fault.message : std::string("the camera is no longer open"));
  }
}

std::string StillCameraTrigger::Describe() const {
  std::lock_guard lock(mutex_);
  return camera_->Name() + " still camera" + (open_ ? " " + model_ : std::string(" (not open)"));
}

StillCameraFault StillCameraTrigger::last_fault() const {
  std::lock_guard lock(mutex_);
  return last_fault_;
}

}  // namespace kapfix::agent
