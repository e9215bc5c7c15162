#pragma once

#include <functional>

#include "agent/commands/state_keeper.hpp"
#include "agent/downlink/video_downlink.hpp"
#include "agent/modes/mode_runner.hpp"
#include "agent/photos/photo_taker.hpp"
#include "agent/server/agent_control.hpp"

namespace kapfix::agent {

// What a command can reach in the agent.
struct CommandTargets {
  StateKeeper& state;
  ModeRunner& modes;
  PhotoTaker& photos;
  VideoDownlink& video;
  // Hands new camera settings to the capture thread (drivers are not thread-safe).
  std::function<void(const kapfix::v1::CameraSettings&)> apply_camera;
  bool free_swing_recording_possible = true;  // a recordings folder is configured
};

// The agent's AgentControl (the seam behind CommandServer): carries out each command that
// passed the validator by updating the settings (StateKeeper) and handing them to the part
// that uses them — modes, photos, video, camera. Refuses only what depends on the agent's
// situation, with the reason. Returns at once: mode switches and photos take effect on the
// next frame and report on the streams.
class CommandExecutor : public AgentControl {
 public:
  explicit CommandExecutor(CommandTargets targets);

  kapfix::v1::Reply Execute(const kapfix::v1::Command& command) override;
  kapfix::v1::AgentState State() const override;

 private:
  kapfix::v1::Reply SetMode(const kapfix::v1::SetMode& set_mode);
  kapfix::v1::Reply ApplySettings(const kapfix::v1::Command& command);

  CommandTargets targets_;
};

}  // namespace kapfix::agent
