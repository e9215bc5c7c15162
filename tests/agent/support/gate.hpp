#pragma once

#include <condition_variable>
#include <mutex>

namespace kapfix::agent::testing {

// An event a thread waits on until the test opens it: a slow disk or device that takes as
// long as the test wants, without any wall-clock wait. Also says whether someone is waiting.
class Gate {
 public:
  // Blocks until Open(); counts as entered meanwhile.
  void Pass() {
    std::unique_lock lock(mutex_);
    ++entered_;
    changed_.notify_all();
    changed_.wait(lock, [this] { return open_; });
  }
  void Open() {
    std::lock_guard lock(mutex_);
    open_ = true;
    changed_.notify_all();
  }
  // Blocks until at least `count` threads reached Pass().
  void WaitEntered(int count = 1) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this, count] { return entered_ >= count; });
  }
  bool holding() const {
    std::lock_guard lock(mutex_);
    return entered_ > 0 && !open_;
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  int entered_ = 0;
  bool open_ = false;
};

}  // namespace kapfix::agent::testing
