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

  std::vector<std::string> args = {
      KAPFIX_AGENT,        "--sim",
      "--scene",           std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg",
      "--command-address", "tcp://127.0.0.1:" + std::to_string(command_port_),
      "--stream-address",  "tcp://127.0.0.1:" + std::to_string(stream_port_),
      "--photos",          photos().string(),
      "--state-dir",       (folder_ / "state").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  process_ = std::make_unique<ChildProcess>(args, folder_ / "agent.out", folder_ / "agent.err");
}

AgentProcess::~AgentProcess() {
  Stop();
  std::error_code ignored;
  std::filesystem::remove_all(folder_, ignored);
}

bool AgentProcess::running() { return process_->running(); }

pid_t AgentProcess::pid() const { return process_->pid(); }

int AgentProcess::Stop() { return process_->Stop(SIGTERM); }

std::string AgentProcess::log() const { return ReadFile(folder_ / "agent.err"); }

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
