#pragma once

#include <memory>
#include <string>

#include "agent/servo/servo_driver.hpp"
#include "common/sim/simulated_platform.hpp"

namespace kapfix::agent {

// The simulated servos of SPEC §3 as a ServoDriver: commands go to the SimulatedPlatform that
// SimFrameSource looks through (latency, rate limit, dead band and backlash are the
// platform's). Like every backend it sits behind LimitedServoDriver.
class SimServoDriver : public ServoDriver {
 public:
  // Throws std::invalid_argument for a null platform.
  explicit SimServoDriver(std::shared_ptr<SimulatedPlatform> platform);

  bool Open(std::string* error) override;
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  bool Park(std::string* error) override;  // commands 0 deg on both axes
  std::string Describe() const override { return "sim servos"; }

 private:
  std::shared_ptr<SimulatedPlatform> platform_;
  bool open_ = false;
};

}  // namespace kapfix::agent
