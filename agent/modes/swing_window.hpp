#pragma once

#include <cstdint>

#include "agent/modes/agent_mode.hpp"
#include "agent/modes/report_messages.hpp"

namespace kapfix::agent {

// The frames a free-swing process (SSP, PSS, recording) runs over: from the frame it started
// on until its deadline in frames or camera seconds, whichever comes first.
struct SwingWindow {
  SwingDeadline deadline;
  std::uint64_t start_index = 0;     // the frame the process started on
  double frame_period_s = 1.0 / 30;  // [s] camera time of one frame

  bool Reached(std::uint64_t index) const {
    const auto frames = static_cast<double>(index - start_index + 1);
    return frames >= deadline.frames || (frames - 1) * frame_period_s >= deadline.seconds;
  }
  SwingProgress Progress(int frames_used, bool done) const {
    SwingProgress progress;
    progress.done = frames_used;
    progress.total = deadline.frames;
    progress.finished = done;
    progress.deadline_reached = done && frames_used < deadline.frames;
    return progress;
  }
};

// Progress reports of a free-swing process every this many frames (and at its end): often
// enough for a live progress bar, rare enough not to flood the link with graphs.
constexpr int kProgressEveryFrames = 5;

}  // namespace kapfix::agent
