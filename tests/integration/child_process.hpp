#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace kapfix::testing {

// A program running in the background, its stdout and stderr written to files; SIGKILLed and
// reaped when it goes out of scope if it still runs.
class ChildProcess {
 public:
  // Starts args[0] (a path) with `args`; throws std::runtime_error when it cannot.
  ChildProcess(const std::vector<std::string>& args, const std::filesystem::path& out,
               const std::filesystem::path& err);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }  // -1 once reaped
  bool running();                     // reaps it when it has exited
  // Sends `signal`, waits up to `grace` for the exit, then SIGKILLs. The exit code; -1 when it
  // did not exit normally (killed by a signal, or not within `grace`).
  int Stop(int signal, std::chrono::milliseconds grace = std::chrono::seconds(10));

 private:
  pid_t pid_ = -1;
  int exit_code_ = -1;
};

}  // namespace kapfix::testing
