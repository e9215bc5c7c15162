#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

namespace kapfix::ctl {

// Messages of one topic handed from the I/O thread to the main thread; only those that
// arrive once armed (right before the command is sent), so an older report cannot pass for
// the answer.
template <typename T>
class Inbox {
 public:
  void Arm() { armed_.store(true); }
  void Put(const T& message) {
    if (!armed_.load()) return;
    {
      const std::lock_guard lock(mutex_);
      messages_.push_back(message);
    }
    arrived_.notify_one();
  }
  std::optional<T> Take(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    if (!arrived_.wait_for(lock, wait, [this] { return !messages_.empty(); })) return std::nullopt;
    T message = std::move(messages_.front());
    messages_.pop_front();
    return message;
  }

 private:
  std::atomic<bool> armed_{false};
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<T> messages_;
};

}  // namespace kapfix::ctl
