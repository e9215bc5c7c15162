#pragma once

#include "agent/resume/resume_recorder.hpp"
#include "agent/server/agent_control.hpp"

namespace kapfix::agent {

// The AgentControl in front of the agent's own (CommandExecutor): passes every command on
// and hands each settings command that was carried out to the ResumeRecorder (issue 14).
class RecordingControl : public AgentControl {
 public:
  RecordingControl(AgentControl& next, ResumeRecorder& recorder);

  kapfix::v1::Reply Execute(const kapfix::v1::Command& command) override;
  kapfix::v1::AgentState State() const override;

 private:
  AgentControl& next_;
  ResumeRecorder& recorder_;
};

}  // namespace kapfix::agent
