#pragma once

#include <string>
#include <vector>

#include "agent/servo/servo_driver.hpp"

namespace kapfix::agent {

// One call that reached FakeServoDriver and succeeded.
struct FakeServoCommand {
  enum class Kind { kSetAngle, kPark };
  Kind kind = Kind::kSetAngle;
  ServoAxis axis = ServoAxis::kPan;  // kSetAngle only
  double deg = 0;                    // [deg] kSetAngle only
};

// A ServoDriver for tests: records every successful command and fails on demand, to exercise
// the decorator and the agent's fault handling without hardware.
class FakeServoDriver : public ServoDriver {
 public:
  bool Open(std::string* error) override;
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  // Records kPark and sets both angles to 0.
  bool Park(std::string* error) override;
  std::string Describe() const override { return "fake servos"; }
  // The angle last commanded or put there by MoveOnItsOwn; fails while not open or when
  // made unreadable.
  bool ReadAngle(ServoAxis axis, double* deg, std::string* error) override;

  // The next Open fails while this is set.
  void FailOpen(bool fail) { fail_open_ = fail; }
  // The next `count` SetAngle/Park calls fail with a reason and move nothing.
  void FailNextCommands(int count) { fail_commands_ = count; }
  // As if the device went away (a USB serial adapter unplugged): every command fails until
  // the next successful Open.
  void Disconnect() { open_ = false; }
  // As if the device moved the servos by itself (a Maestro's serial timeout sending them
  // home): the angles change without a command.
  void MoveOnItsOwn(double pan_deg, double tilt_deg) {
    pan_deg_ = pan_deg;
    tilt_deg_ = tilt_deg;
  }
  // ReadAngle fails while this is false (a backend that cannot read positions).
  void SetReadable(bool readable) { readable_ = readable; }

  const std::vector<FakeServoCommand>& commands() const { return commands_; }
  double angle(ServoAxis axis) const;  // [deg] last successful command
  int open_count() const { return open_count_; }

 private:
  bool CommandFails(std::string* error);

  std::vector<FakeServoCommand> commands_;
  double pan_deg_ = 0;
  double tilt_deg_ = 0;
  bool open_ = false;
  bool fail_open_ = false;
  bool readable_ = true;
  int fail_commands_ = 0;
  int open_count_ = 0;
};

}  // namespace kapfix::agent
