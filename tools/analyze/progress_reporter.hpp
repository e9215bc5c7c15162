#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace kapfix::analyze {

// Progress on stderr for work longer than a second (stdout carries the JSON). Silent for the
// first second, then at most four updates a second: a rewritten line on a terminal, a line
// every 10 % otherwise (logs, CI).
class ProgressReporter {
 public:
  explicit ProgressReporter(std::string label, std::FILE* stream = stderr);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void Update(int done, int total);
  // Sets what is being worked on now (e.g. "slice 3/9"); shown before the fraction.
  void SetStage(std::string stage);

 private:
  std::string label_;
  std::string stage_;
  std::FILE* stream_;
  bool terminal_;
  bool shown_ = false;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
};

}  // namespace kapfix::analyze
