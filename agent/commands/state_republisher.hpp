#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "agent/commands/state_keeper.hpp"

namespace kapfix::agent {

// Publishes the agent's state again at a low rate, so that a state lost on the link (a full
// queue, a station that subscribed a moment too late) heals by itself within one interval
// instead of standing until the next change. Its own thread; stops when destroyed.
class StateRepublisher {
 public:
  // [ms] about 1 Hz: cheap next to telemetry, and a stale state never stands long.
  static constexpr std::chrono::milliseconds kDefaultInterval{1000};

  explicit StateRepublisher(StateKeeper& state,
                            std::chrono::milliseconds interval = kDefaultInterval);
  ~StateRepublisher();
  StateRepublisher(const StateRepublisher&) = delete;
  StateRepublisher& operator=(const StateRepublisher&) = delete;

 private:
  void Loop();

  StateKeeper& state_;
  std::chrono::milliseconds interval_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;  // last: starts after everything it uses
};

}  // namespace kapfix::agent
