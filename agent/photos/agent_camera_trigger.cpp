#include "agent/photos/agent_camera_trigger.hpp"

#include <stdexcept>

#include "agent/photos/photo_store.hpp"

namespace kapfix::agent {

bool AgentCameraTrigger::Take(const PhotoRequest& request, TakenPhoto* photo, std::string* error) {
  if (request.agent_frame.empty()) {
    if (error) *error = "the agent's camera: no frame to store";
    return false;
  }
  try {
    photo->bytes = PhotoStore::EncodeJpeg(request.agent_frame);
  } catch (const std::runtime_error& e) {
    if (error) *error = e.what();
    return false;
  }
  photo->format = "jpeg";
  photo->width_px = static_cast<std::uint32_t>(request.agent_frame.cols);
  photo->height_px = static_cast<std::uint32_t>(request.agent_frame.rows);
  photo->camera = kapfix::v1::PHOTO_CAMERA_AGENT;
  photo->camera_path.clear();
  return true;
}

}  // namespace kapfix::agent
