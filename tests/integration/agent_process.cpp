#include "tests/integration/agent_process.hpp"

#include <signal.h>
#include <stdlib.h>

#include <stdexcept>

#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {

AgentProcess::AgentProcess(const std::vector<std::string>& extra) {
  std::string pattern =
      (std::filesystem::temp_directory_path() / "kapfix_integration_XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  folder_ = pattern;
  UnusedPort command;
  UnusedPort stream;
  command_port_ = command.port();
  stream_port_ = stream.port();
  command.Release();
  stream.Release();

  extra_ = extra;
  Start(extra);
}

void AgentProcess::Start(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {
      KAPFIX_AGENT,        "--sim",
      "--scene",           std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg",
      "--command-address", command_endpoint(),
      "--stream-address",  stream_endpoint(),
      "--photos",          photos().string(),
      "--state-dir",       state_dir().string()};
  args.insert(args.end(), extra.begin(), extra.end());
  ++starts_;
  const std::string suffix = starts_ == 1 ? "" : "." + std::to_string(starts_);
  process_ = std::make_unique<ChildProcess>(args, folder_ / ("agent" + suffix + ".out"),
                                            ErrorLog(starts_));
}

std::filesystem::path AgentProcess::ErrorLog(int start) const {
  return folder_ /
         (start == 1 ? std::string("agent.err") : "agent." + std::to_string(start) + ".err");
}

AgentProcess::~AgentProcess() {
  Stop();
  std::error_code ignored;
  std::filesystem::remove_all(folder_, ignored);
}

bool AgentProcess::running() { return process_->running(); }

pid_t AgentProcess::pid() const { return process_->pid(); }

int AgentProcess::Stop() { return process_->Stop(SIGTERM); }

void AgentProcess::Kill() { process_->Stop(SIGKILL); }

void AgentProcess::Restart(const std::vector<std::string>& extra) {
  if (process_->running()) throw std::logic_error("restart of an agent that still runs");
  // The same ports: the new agent binds them again (ZeroMQ listens with SO_REUSEADDR, so the
  // old agent's connections in TIME_WAIT do not stand in the way).
  Start(extra);
}

std::string AgentProcess::log() const {
  std::string text = ReadFile(ErrorLog(1));
  for (int start = 2; start <= starts_; ++start) {
    text += "--- start " + std::to_string(start) + " ---\n" + ReadFile(ErrorLog(start));
  }
  return text;
}

std::vector<std::string> AgentProcess::CtlCommand(const std::vector<std::string>& args) const {
  std::vector<std::string> command = {KAPFIX_CTL,
                                      "--agent",
                                      "127.0.0.1",
                                      "--command-port",
                                      std::to_string(command_port_),
                                      "--stream-port",
                                      std::to_string(stream_port_),
                                      "--timeout",
                                      "5000"};
  command.insert(command.end(), args.begin(), args.end());
  return command;
}

AgentProcess::CtlOutcome AgentProcess::Ctl(const std::string& args) const {
  std::string command_line;
  for (const std::string& word : CtlCommand({})) command_line += word + " ";
  const ProcessOutcome run = RunProcess(command_line + args, folder_ / "ctl.err");
  return {run.exit_code, run.out, run.err};
}

}  // namespace kapfix::testing
