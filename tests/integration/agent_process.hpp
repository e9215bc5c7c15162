#pragma once

#include <sys/types.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tests/integration/child_process.hpp"

namespace kapfix::testing {

// kapfix-agent as a child process in simulation (real time), on free loopback ports with a
// private folder for its photos, state, log and report. Stopped with SIGTERM when it goes out
// of scope. It can be killed and started again on the same endpoints and folders, as an
// operator restarts a crashed agent (issue 14).
class AgentProcess {
 public:
  // `extra` arguments are added to "--sim --command-address … --stream-address … --photos …".
  explicit AgentProcess(const std::vector<std::string>& extra = {});
  ~AgentProcess();
  AgentProcess(const AgentProcess&) = delete;
  AgentProcess& operator=(const AgentProcess&) = delete;

  // SIGTERM, then waits; the exit code (-1 when it did not exit normally within 10 s).
  int Stop();
  // kill -9: no goodbye on the link, nothing flushed; returns once it is reaped.
  void Kill();
  // Starts the agent again after Stop or Kill, on the same endpoints, photo and state folders,
  // with `extra` in place of the first start's extra arguments. Throws std::logic_error while
  // the previous one still runs.
  void Restart(const std::vector<std::string>& extra);
  void Restart() { Restart(extra_); }  // with the first start's extra arguments
  bool running();                      // reaps it when it has exited
  pid_t pid() const;                   // -1 once it has exited and been reaped

  int command_port() const { return command_port_; }
  int stream_port() const { return stream_port_; }
  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path photos() const { return folder_ / "photos"; }
  // --state-dir: what a restart resumes from.
  std::filesystem::path state_dir() const { return folder_ / "state"; }
  std::string command_endpoint() const {
    return "tcp://127.0.0.1:" + std::to_string(command_port_);
  }
  std::string stream_endpoint() const { return "tcp://127.0.0.1:" + std::to_string(stream_port_); }
  std::string log() const;  // what every start wrote on stderr so far

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
  std::vector<std::string> extra_;  // the first start's extra arguments
  int starts_ = 0;                  // [count] starts so far; each has its own log
  std::unique_ptr<ChildProcess> process_;

  void Start(const std::vector<std::string>& extra);
  std::filesystem::path ErrorLog(int start) const;
};

}  // namespace kapfix::testing
