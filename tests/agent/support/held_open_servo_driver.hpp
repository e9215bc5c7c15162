#pragma once

#include <atomic>
#include <string>

#include "agent/servo/fake_servo_driver.hpp"
#include "tests/agent/support/gate.hpp"

namespace kapfix::agent::testing {

// A servo driver whose Open, once held, waits until the test releases it (a Maestro taking its
// answer timeout, a slow USB setup): as long as the test wants, without a wall-clock wait.
class HeldOpenServoDriver : public FakeServoDriver {
 public:
  bool Open(std::string* error) override {
    if (hold_) gate_.Pass();
    return FakeServoDriver::Open(error);
  }
  // From now on Open waits for Release().
  void Hold() { hold_ = true; }
  // Blocks until a thread is inside Open.
  void WaitUntilOpening() { gate_.WaitEntered(); }
  void Release() { gate_.Open(); }
  bool opening() const { return gate_.holding(); }

 private:
  std::atomic<bool> hold_{false};
  Gate gate_;
};

}  // namespace kapfix::agent::testing
