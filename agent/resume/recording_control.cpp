#include "agent/resume/recording_control.hpp"

#include "agent/commands/settings_messages.hpp"

namespace kapfix::agent {

RecordingControl::RecordingControl(AgentControl& next, ResumeRecorder& recorder)
    : next_(next), recorder_(recorder) {}

kapfix::v1::Reply RecordingControl::Execute(const kapfix::v1::Command& command) {
  kapfix::v1::Reply reply = next_.Execute(command);
  if (!reply.ok()) return reply;
  if (IsSettingsCommand(command)) recorder_.OnSettingsApplied(command);
  return reply;
}

kapfix::v1::AgentState RecordingControl::State() const { return next_.State(); }

}  // namespace kapfix::agent
