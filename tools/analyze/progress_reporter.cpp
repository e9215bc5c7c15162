#include "tools/analyze/progress_reporter.hpp"

#include <unistd.h>

namespace kapfix::analyze {

ProgressReporter::ProgressReporter(std::string label, std::FILE* stream)
    : label_(std::move(label)),
      stream_(stream),
      terminal_(isatty(fileno(stream)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

ProgressReporter::~ProgressReporter() {
  if (shown_ && terminal_) std::fputc('\n', stream_);
}

void ProgressReporter::SetStage(std::string stage) { stage_ = std::move(stage); }

void ProgressReporter::Update(int done, int total) {
  using namespace std::chrono_literals;
  const auto now = std::chrono::steady_clock::now();
  if (now - start_ < 1s || total <= 0) return;
  const int percent = static_cast<int>(100LL * done / total);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = done > 0 ? elapsed * (total - done) / done : 0.0;
  const std::string where = stage_.empty() ? "" : stage_ + " ";
  if (terminal_) {
    if (now - last_print_ < 250ms && done < total) return;
    std::fprintf(stream_, "\r%s: %s%3d%% (%d/%d) %.0fs left   ", label_.c_str(), where.c_str(),
                 percent, done, total, eta);
  } else {
    const int decile = percent / 10;
    if (decile == last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stream_, "%s: %s%d%% (%d/%d)\n", label_.c_str(), where.c_str(), percent, done,
                 total);
  }
  std::fflush(stream_);
  last_print_ = now;
  shown_ = true;
}

}  // namespace kapfix::analyze
