#pragma once

#include <cstdint>
#include <string>

#include "agent/servo/servo_channel_mapping.hpp"
#include "agent/servo/servo_driver.hpp"

namespace kapfix::agent {

struct MaestroServoDriverOptions {
  // The Maestro's Command Port (USB: the first of its two ttyACM ports) or a UART.
  std::string device = "/dev/ttyACM0";
  // [bit/s] 9600, 19200, 38400, 57600 or 115200. Over USB the Command Port ignores it; on a
  // UART it must equal the Maestro's "fixed baud rate" serial setting.
  int baud = 115200;
  ServoChannelMapping pan{.channel = 0};
  ServoChannelMapping tilt{.channel = 1};
  int answer_timeout_ms = 500;  // [ms] how long Open waits for the answer to Get Errors

  bool IsValid(std::string* error) const;
};

// A Pololu Maestro (Micro 6 or Mini 12/18/24) driven with the compact serial protocol:
// Set Target (0x84) with the pulse width in quarter-µs, through ServoChannelMapping.
//
// Serial timeout — what happens if the agent dies. The Maestro's "Timeout" (Control Center,
// Serial Settings tab; 0.01 s resolution, 0.01…655.35 s, 0 = off, off by default) raises a
// serial timeout error (bit 5) when no valid serial command arrives for that long, and every
// error sends each servo to its home position ("On startup or error": Go to / Off / Ignore,
// per channel, Off by default). It is a persistent device setting: the serial protocol has no
// command to read or write it (only native USB requests do, as Pololu's Control Center and
// UscCmd use), so the agent does not set it. Configure it once per Maestro:
//   Timeout = 0.5 s (agent watchdog or less), and for the pan and tilt channels
//   "On startup or error" = Go to <the pulse of ServoLimits::park_deg> (1500 µs at 0 deg).
// What Open verifies: the Maestro answers Get Errors (0xA1) in time, i.e. the port, serial
// mode and baud rate are right. Get Errors also clears the register; a serial-timeout bit
// found there is logged, as it shows the timeout is enabled and fired since the last run.
// The agent must then send a command at least once per timeout period: the control loop
// commands every frame and the watchdog parks (a command too) when the loop stalls.
//
// Not thread-safe; one owner (the control loop) calls it.
class MaestroServoDriver : public ServoDriver {
 public:
  explicit MaestroServoDriver(MaestroServoDriverOptions options);
  ~MaestroServoDriver() override;
  MaestroServoDriver(const MaestroServoDriver&) = delete;
  MaestroServoDriver& operator=(const MaestroServoDriver&) = delete;

  // Opens and configures the port (raw, 8N1, baud), then checks the Maestro answers.
  bool Open(std::string* error) override;
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  // Set Target 0 deg (the centre pulse) on both channels.
  bool Park(std::string* error) override;
  std::string Describe() const override;

  // Reads and clears the Maestro's error register (Get Errors).
  bool GetErrors(std::uint16_t* errors, std::string* error);

 private:
  bool Fail(const std::string& reason, std::string* error) const;
  bool Write(const std::uint8_t* bytes, std::size_t count, std::string* error);
  void Close();

  MaestroServoDriverOptions options_;
  int fd_ = -1;
};

}  // namespace kapfix::agent
