#include "tests/integration/agent_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "tests/link/link_test_support.hpp"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, for posix_spawn

namespace kapfix::testing {
namespace {}  // namespace

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
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string out = (folder_ / "agent.out").string();
  const std::string err = (folder_ / "agent.err").string();
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int failed = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed != 0) throw std::runtime_error("cannot start " + args[0]);
}

AgentProcess::~AgentProcess() {
  Stop();
  std::error_code ignored;
  std::filesystem::remove_all(folder_, ignored);
}

bool AgentProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == 0) return true;
  pid_ = -1;
  exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return false;
}

int AgentProcess::Stop() {
  if (pid_ <= 0) return exit_code_;
  ::kill(pid_, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  int status = 0;
  while (::waitpid(pid_, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, &status, 0);
      pid_ = -1;
      return exit_code_ = -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  pid_ = -1;
  exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return exit_code_;
}

std::string AgentProcess::log() const { return ReadFile(folder_ / "agent.err"); }

AgentProcess::CtlOutcome AgentProcess::Ctl(const std::string& args) const {
  const std::filesystem::path err_file = folder_ / "ctl.err";
  const std::string command = std::string(KAPFIX_CTL) + " --agent 127.0.0.1 --command-port " +
                              std::to_string(command_port_) + " --stream-port " +
                              std::to_string(stream_port_) + " --timeout 5000 " + args;
  const ProcessOutcome run = RunProcess(command, err_file);
  return {run.exit_code, run.out, run.err};
}

}  // namespace kapfix::testing
