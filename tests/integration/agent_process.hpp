#pragma once

#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tests/integration/child_process.hpp"

namespace kapfix::testing {

// kapfix-agent as a child process in simulation (real time), on free loopback ports with a
// private folder for its photos, log and report. Stopped with SIGTERM when it goes out of
// scope.
class AgentProcess {
 public:
  // `extra` arguments are added to "--sim --command-address … --stream-address … --photos …".
  explicit AgentProcess(const std::vector<std::string>& extra = {});
  ~AgentProcess();
  AgentProcess(const AgentProcess&) = delete;
  AgentProcess& operator=(const AgentProcess&) = delete;

  // SIGTERM, then waits; the exit code (-1 when it did not exit normally within 10 s).
  int Stop();
  bool running();     // reaps it when it has exited
  pid_t pid() const;  // -1 once it has exited and been reaped

  int command_port() const { return command_port_; }
  int stream_port() const { return stream_port_; }
  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path photos() const { return folder_ / "photos"; }
  std::string command_endpoint() const {
    return "tcp://127.0.0.1:" + std::to_string(command_port_);
  }
  std::string stream_endpoint() const { return "tcp://127.0.0.1:" + std::to_string(stream_port_); }
  std::string log() const;  // what it wrote on stderr so far

  // kapfix-ctl pointed at this agent: exit code and stdout; stderr goes to ctl_err.
  struct CtlOutcome {
    int exit_code = -1;
    std::string out;
    std::string err;
  };
  CtlOutcome Ctl(const std::string& args) const;
  // kapfix-ctl's arguments pointed at this agent, then `args`: e.g. for a station run in the
  // background as a ChildProcess.
  std::vector<std::string> CtlCommand(const std::vector<std::string>& args) const;

 private:
  std::filesystem::path folder_;
  int command_port_ = 0;
  int stream_port_ = 0;
  std::unique_ptr<ChildProcess> process_;
};

}  // namespace kapfix::testing
