#include "agent/commands/state_republisher.hpp"

namespace kapfix::agent {

StateRepublisher::StateRepublisher(StateKeeper& state, std::chrono::milliseconds interval)
    : state_(state), interval_(interval), thread_([this] { Loop(); }) {}

StateRepublisher::~StateRepublisher() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void StateRepublisher::Loop() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, interval_, [this] { return stop_; })) {
    lock.unlock();
    state_.PublishState();
    lock.lock();
  }
}

}  // namespace kapfix::agent
