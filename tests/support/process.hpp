#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace kapfix::testing {

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

// A command line run as a script runs it (popen): its exit code (-1 when it did not exit
// normally), its stdout, and its stderr, which the command line redirects to `err_file`.
struct ProcessOutcome {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline ProcessOutcome RunProcess(const std::string& command_line,
                                 const std::filesystem::path& err_file) {
  ProcessOutcome outcome;
  FILE* pipe = ::popen((command_line + " 2>" + err_file.string()).c_str(), "r");
  if (pipe == nullptr) return outcome;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) outcome.out += buffer.data();
  const int status = ::pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  outcome.err = ReadFile(err_file);
  return outcome;
}

}  // namespace kapfix::testing
