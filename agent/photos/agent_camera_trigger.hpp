#pragma once

#include "agent/photos/photo_trigger.hpp"

namespace kapfix::agent {

// The agent's own camera as a PhotoTrigger: the request's frame, encoded as JPEG. Never
// fails on a frame it was given; it is the fallback of every other camera.
class AgentCameraTrigger : public PhotoTrigger {
 public:
  bool Take(const PhotoRequest& request, TakenPhoto* photo, std::string* error) override;
  std::string Describe() const override { return "the agent's camera"; }
};

}  // namespace kapfix::agent
