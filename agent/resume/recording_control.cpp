#include "agent/resume/recording_control.hpp"

namespace kapfix::agent {

RecordingControl::RecordingControl(AgentControl& next, ResumeRecorder& recorder)
    : next_(next), recorder_(recorder) {}

kapfix::v1::Reply RecordingControl::Execute(const kapfix::v1::Command& command) {
  kapfix::v1::Reply reply = next_.Execute(command);
  if (!reply.ok()) return reply;
  switch (command.command_case()) {
    case kapfix::v1::Command::kSetGains:
    case kapfix::v1::Command::kSetSearch:
    case kapfix::v1::Command::kSetCamera:
    case kapfix::v1::Command::kSetLens:
    case kapfix::v1::Command::kSetVideo:
    case kapfix::v1::Command::kSetPhotoIntervalS:
    case kapfix::v1::Command::kSetPhoto:
      recorder_.OnSettingsApplied(command);
      break;
    default:
      break;
  }
  return reply;
}

kapfix::v1::AgentState RecordingControl::State() const { return next_.State(); }

}  // namespace kapfix::agent
