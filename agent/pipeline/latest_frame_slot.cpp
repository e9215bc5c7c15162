#include "agent/pipeline/latest_frame_slot.hpp"

namespace kapfix::agent {

void LatestFrameSlot::Put(CapturedFrame frame) {
  {
    std::lock_guard lock(mutex_);
    if (closed_) return;
    if (frame_) ++dropped_;
    frame_ = std::move(frame);
  }
  changed_.notify_all();
}

std::optional<CapturedFrame> LatestFrameSlot::Take() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return frame_.has_value() || closed_; });
  if (!frame_) return std::nullopt;
  std::optional<CapturedFrame> out = std::move(frame_);
  frame_.reset();
  ++delivered_;
  return out;
}

void LatestFrameSlot::Close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

void LatestFrameSlot::MarkDone(std::uint64_t index) {
  {
    std::lock_guard lock(mutex_);
    done_ = index;
  }
  changed_.notify_all();
}

bool LatestFrameSlot::WaitDone(std::uint64_t index) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this, index] { return closed_ || (done_ && *done_ >= index); });
  return done_ && *done_ >= index;
}

std::uint64_t LatestFrameSlot::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

std::uint64_t LatestFrameSlot::delivered() const {
  std::lock_guard lock(mutex_);
  return delivered_;
}

}  // namespace kapfix::agent
