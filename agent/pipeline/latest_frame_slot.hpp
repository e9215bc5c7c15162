#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>

#include "agent/capture/frame_source.hpp"

namespace kapfix::agent {

// The capture → control handoff: holds only the latest frame. A Put over a frame the control
// thread has not taken yet replaces it, and the replaced frame is counted as dropped (SPEC §4:
// stale frames are dropped, and the counters say so). Thread-safe; one producer, one consumer.
class LatestFrameSlot {
 public:
  // Stores the frame, replacing (and counting) one not taken yet. Ignored after Close.
  void Put(CapturedFrame frame);
  // Waits for a frame; nullopt once closed and empty.
  std::optional<CapturedFrame> Take();
  // Wakes Take; the frame still in the slot is handed out first.
  void Close();

  // Lock-step (simulation): the consumer reports that it finished frame `index`, and the
  // producer waits for that before grabbing the next. WaitDone returns false when closed.
  void MarkDone(std::uint64_t index);
  bool WaitDone(std::uint64_t index);

  std::uint64_t dropped() const;
  std::uint64_t delivered() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<CapturedFrame> frame_;
  std::optional<std::uint64_t> done_;
  bool closed_ = false;
  std::uint64_t dropped_ = 0;
  std::uint64_t delivered_ = 0;
};

}  // namespace kapfix::agent
