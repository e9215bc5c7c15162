#include "agent/still_camera/gphoto2_still_camera.hpp"

#include <gphoto2/gphoto2-camera.h>
#include <gphoto2/gphoto2-context.h>
#include <gphoto2/gphoto2-file.h>
#include <gphoto2/gphoto2-list.h>
#include <gphoto2/gphoto2-port-result.h>
#include <gphoto2/gphoto2-result.h>

#include <cstring>
#include <utility>

namespace kapfix::agent {

struct Gphoto2StillCamera::Impl {
  GPContext* context = nullptr;
  Camera* camera = nullptr;
  std::string context_error;  // the library's own words for the last error, if it gave any
};

namespace {

// The library's detail, e.g. "Could not claim the USB device", follows its result code.
std::string Describe(int result, const std::string& step, std::string* context_error) {
  std::string message = step + ": " + gp_result_as_string(result);
  if (!context_error->empty()) message += " (" + *context_error + ")";
  context_error->clear();
  return message;
}

// What the operator can do about `result`; `transferring`: the camera had been answering.
StillCameraFault FaultOf(int result, bool transferring) {
  switch (result) {
    case GP_ERROR_CAMERA_BUSY:
    case GP_ERROR_IO_USB_CLAIM:  // another program (gvfs, a file manager) holds the camera
    case GP_ERROR_IO_LOCK:
      return StillCameraFault::kBusy;
    case GP_ERROR_MODEL_NOT_FOUND:
    case GP_ERROR_IO_USB_FIND:
    case GP_ERROR_IO:
    case GP_ERROR_IO_INIT:
    case GP_ERROR_IO_READ:
    case GP_ERROR_IO_WRITE:
    case GP_ERROR_IO_UPDATE:
    case GP_ERROR_TIMEOUT:
    case GP_ERROR_IO_USB_CLEAR_HALT:
      return transferring ? StillCameraFault::kVanished : StillCameraFault::kAbsent;
    default:  // not supported, camera error, file not found…: it answered and said no
      return StillCameraFault::kRefused;
  }
}

bool Failed(int result, const std::string& step, bool transferring, std::string* context_error,
            StillCameraError* error) {
  if (error) *error = {FaultOf(result, transferring), Describe(result, step, context_error)};
  return false;
}

// "/store_00010001/DCIM/IMG_0001.JPG" → folder "/store_00010001/DCIM", name "IMG_0001.JPG".
std::pair<std::string, std::string> Split(const std::string& camera_path) {
  const std::size_t slash = camera_path.rfind('/');
  if (slash == std::string::npos) return {"/", camera_path};
  return {slash == 0 ? std::string("/") : camera_path.substr(0, slash),
          camera_path.substr(slash + 1)};
}

extern "C" void OnContextError(GPContext* /*context*/, const char* text, void* data) {
  if (text != nullptr) *static_cast<std::string*>(data) = text;
}

}  // namespace

Gphoto2StillCamera::Gphoto2StillCamera() : impl_(std::make_unique<Impl>()) {}

Gphoto2StillCamera::~Gphoto2StillCamera() { Close(); }

bool Gphoto2StillCamera::Available() { return true; }

bool Gphoto2StillCamera::Open(std::string* model, StillCameraError* error) {
  Close();
  impl_->context = gp_context_new();
  if (impl_->context == nullptr) {
    if (error) *error = {StillCameraFault::kAbsent, "libgphoto2: no context (out of memory)"};
    return false;
  }
  gp_context_set_error_func(impl_->context, OnContextError, &impl_->context_error);
  CameraList* list = nullptr;
  if (const int result = gp_list_new(&list); result < GP_OK) {
    return Failed(result, "detecting cameras", false, &impl_->context_error, error);
  }
  const int found = gp_camera_autodetect(list, impl_->context);
  std::string name;
  std::string port;
  if (found > 0) {
    const char* text = nullptr;
    if (gp_list_get_name(list, 0, &text) == GP_OK && text != nullptr) name = text;
    if (gp_list_get_value(list, 0, &text) == GP_OK && text != nullptr) port = text;
  }
  gp_list_free(list);
  if (found < 0) return Failed(found, "detecting cameras", false, &impl_->context_error, error);
  if (found == 0) {
    if (error) {
      *error = {StillCameraFault::kAbsent,
                "no camera found (is it connected by USB, switched on and in PTP mode?)"};
    }
    return false;
  }
  if (const int result = gp_camera_new(&impl_->camera); result < GP_OK) {
    impl_->camera = nullptr;
    return Failed(result, "opening " + name, false, &impl_->context_error, error);
  }
  // Initialises the first camera detected, as gp_camera_autodetect listed it.
  if (const int result = gp_camera_init(impl_->camera, impl_->context); result < GP_OK) {
    gp_camera_unref(impl_->camera);
    impl_->camera = nullptr;
    return Failed(result, "opening " + name + " on " + port, false, &impl_->context_error, error);
  }
  if (model) *model = name + " on " + port;
  return true;
}

void Gphoto2StillCamera::Close() {
  if (impl_->camera != nullptr) {
    gp_camera_exit(impl_->camera, impl_->context);
    gp_camera_unref(impl_->camera);
    impl_->camera = nullptr;
  }
  if (impl_->context != nullptr) {
    gp_context_unref(impl_->context);
    impl_->context = nullptr;
  }
}

bool Gphoto2StillCamera::Capture(std::string* camera_path, StillCameraError* error) {
  if (impl_->camera == nullptr) {
    if (error) *error = {StillCameraFault::kAbsent, "capture: the camera is not open"};
    return false;
  }
  CameraFilePath path{};
  if (const int result = gp_camera_capture(impl_->camera, GP_CAPTURE_IMAGE, &path, impl_->context);
      result < GP_OK) {
    return Failed(result, "capture", true, &impl_->context_error, error);
  }
  const std::string folder(path.folder, strnlen(path.folder, sizeof(path.folder)));
  const std::string name(path.name, strnlen(path.name, sizeof(path.name)));
  *camera_path = folder.ends_with('/') ? folder + name : folder + "/" + name;
  return true;
}

bool Gphoto2StillCamera::Download(const std::string& camera_path, std::string* bytes,
                                  std::string* mime, StillCameraError* error) {
  bytes->clear();
  mime->clear();
  if (impl_->camera == nullptr) {
    if (error) *error = {StillCameraFault::kAbsent, "download: the camera is not open"};
    return false;
  }
  CameraFile* file = nullptr;
  if (const int result = gp_file_new(&file); result < GP_OK) {
    return Failed(result, "download", true, &impl_->context_error, error);
  }
  const auto [folder, name] = Split(camera_path);
  int result = gp_camera_file_get(impl_->camera, folder.c_str(), name.c_str(), GP_FILE_TYPE_NORMAL,
                                  file, impl_->context);
  const char* data = nullptr;
  unsigned long size = 0;  // NOLINT(google-runtime-int): the library's type
  const char* type = nullptr;
  if (result >= GP_OK) result = gp_file_get_data_and_size(file, &data, &size);
  if (result >= GP_OK) result = gp_file_get_mime_type(file, &type);
  if (result >= GP_OK) {
    bytes->assign(data, size);
    if (type != nullptr) *mime = type;
  }
  gp_file_unref(file);
  if (result < GP_OK) return Failed(result, "download", true, &impl_->context_error, error);
  return true;
}

bool Gphoto2StillCamera::Delete(const std::string& camera_path, StillCameraError* error) {
  if (impl_->camera == nullptr) {
    if (error) *error = {StillCameraFault::kAbsent, "delete: the camera is not open"};
    return false;
  }
  const auto [folder, name] = Split(camera_path);
  if (const int result =
          gp_camera_file_delete(impl_->camera, folder.c_str(), name.c_str(), impl_->context);
      result < GP_OK) {
    return Failed(result, "delete", true, &impl_->context_error, error);
  }
  return true;
}

}  // namespace kapfix::agent
