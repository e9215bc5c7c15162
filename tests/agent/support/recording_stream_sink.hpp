#pragma once

#include <google/protobuf/message.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "agent/server/stream_sink.hpp"

namespace kapfix::agent::testing {

// A StreamSink that keeps a copy of every message it accepts (thread-safe), and refuses the
// next `refusals` messages when told to, as a full link queue would.
class RecordingStreamSink : public StreamSink {
 public:
  bool Publish(const google::protobuf::Message& message) override {
    std::lock_guard lock(mutex_);
    if (refusals_ > 0) {
      --refusals_;
      return false;
    }
    std::unique_ptr<google::protobuf::Message> copy(message.New());
    copy->CopyFrom(message);
    messages_.push_back(std::move(copy));
    return true;
  }

  void RefuseNext(int refusals) {
    std::lock_guard lock(mutex_);
    refusals_ = refusals;
  }

  // Copies of the accepted messages of type T, in publishing order.
  template <typename T>
  std::vector<T> Messages() const {
    std::lock_guard lock(mutex_);
    std::vector<T> found;
    for (const auto& message : messages_) {
      if (const auto* typed = dynamic_cast<const T*>(message.get())) found.push_back(*typed);
    }
    return found;
  }

  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return messages_.size();
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<google::protobuf::Message>> messages_;
  int refusals_ = 0;
};

// Polls `done` until it holds or `timeout` passes; the result of the last poll. For the
// agent's asynchronous writer and encoder threads: a test never waits without a bound.
inline bool WaitUntil(const std::function<bool()>& done,
                      std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= deadline) return done();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

}  // namespace kapfix::agent::testing
