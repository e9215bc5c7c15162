#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "agent/servo/maestro_usb_port.hpp"
#include "agent/servo/maestro_usb_setup.hpp"
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
  // [ms] the Maestro's serial timeout, set at Open over native USB: with no serial command
  // for this long, it sends pan and tilt to their home positions. 10…60000, 10 ms steps.
  int serial_timeout_ms = 500;
  double pan_home_deg = 0;   // [deg] pan's home (ServoLimits::park_deg), through `pan`
  double tilt_home_deg = 0;  // [deg] tilt's home, through `tilt`
  // [deg/s] each axis's rate limit (ServoLimits::max_rate_deg_per_s), set at Open as the
  // Maestro's own speed limit on the channel, so that it never slews a servo faster even
  // when it moves one by itself (going home on a serial timeout). 0 = leave the Maestro's.
  double pan_max_rate_deg_per_s = 0;
  double tilt_max_rate_deg_per_s = 0;
  // [ms] time the Maestro's acceleration limit takes to reach that speed from rest.
  int acceleration_ramp_ms = 20;
  // [ms] longest a command may wait for the port to take it: a wedged port fails the command
  // (a driver outage) instead of blocking the control loop or the watchdog's park.
  int write_timeout_ms = 50;

  bool IsValid(std::string* error) const;

  // The serial timeout and the two channels' homes [quarter-µs] for the Maestro's USB setup.
  MaestroUsbSettings UsbSettings() const;
};

// A Pololu Maestro (Micro 6 or Mini 12/18/24) driven with the compact serial protocol:
// Set Target (0x84) with the pulse width in quarter-µs, through ServoChannelMapping.
//
// Serial timeout — what happens if the agent dies. The Maestro's serial timeout (0.01 s
// steps, 0 = off, off by default) raises a serial timeout error (bit 5) when no valid serial
// command arrives for that long, and every error sends each servo to its home position ("On
// startup or error": Go to / Off / Ignore per channel, Off by default). Both are persistent
// device settings that the serial protocol cannot reach, so Open sets them over the Maestro's
// native USB interface (MaestroUsbPort, by default LibusbMaestroUsbPort; see
// ApplyMaestroUsbSettings): timeout = serial_timeout_ms, and pan and tilt "Go to" the pulse
// of their *_home_deg (park_deg). Parameters already right are not rewritten; written ones
// are read back and compared, and the outcome is logged. If that fails (no permission: the
// udev rule; a Maestro on TTL serial only, without USB; built without libusb), Open logs a
// warning naming the cause, what to do and the values to set by hand in Pololu's Control
// Center, and still succeeds: the serial Command Port does not need USB.
// Open does the USB part first: a factory-fresh Maestro is in serial mode "UART, detect baud
// rate" and ignores the Command Port until set to "USB Dual Port" (written like the other
// parameters: only if it differs, then read back). Over USB it also reads each channel's own
// Min/Max (the Maestro clamps targets into them, factory 992…2000 µs) and refuses to open if
// the mapping's [min_us, max_us] reaches beyond them, naming the values to set. After the
// serial check it sets each channel's speed and acceleration limit from the axis's rate
// limit (volatile settings, sent at every Open).
// The port is non-blocking: writes wait at most write_timeout_ms (poll), answers at most
// answer_timeout_ms; EIO (the Maestro unplugged) and a wedged port fail the command.
// What Open verifies on the serial side: the Maestro answers Get Errors (0xA1) in time, i.e.
// the port, serial mode and baud rate are right. Get Errors also clears the register; a
// serial-timeout bit found there is logged, as it shows the timeout fired since the last run.
// The agent must then send a command at least once per timeout period: the control loop
// commands every frame and the watchdog parks (a command too) when the loop stalls; hence
// frame period < serial_timeout_ms ≤ watchdog (checked in AgentConfig::IsValid).
//
// Not thread-safe; one owner (the control loop) calls it.
class MaestroServoDriver : public ServoDriver {
 public:
  // `usb` reaches the Maestro's native USB interface; nullptr = LibusbMaestroUsbPort on
  // options.device.
  explicit MaestroServoDriver(MaestroServoDriverOptions options,
                              std::unique_ptr<MaestroUsbPort> usb = nullptr);
  ~MaestroServoDriver() override;
  MaestroServoDriver(const MaestroServoDriver&) = delete;
  MaestroServoDriver& operator=(const MaestroServoDriver&) = delete;

  // Opens and configures the port (raw, 8N1, baud), checks the Maestro answers, then sets
  // its serial timeout and home positions over USB (a failure there is only a warning).
  bool Open(std::string* error) override;
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  // Set Target 0 deg (the centre pulse) on both channels.
  bool Park(std::string* error) override;
  // Get Position (0x90): the channel's current pulse (mid-slew under the speed limit) as an
  // angle through the mapping. False if the Maestro does not answer or the channel is off.
  bool ReadAngle(ServoAxis axis, double* deg, std::string* error) override;
  std::string Describe() const override;

  // Reads and clears the Maestro's error register (Get Errors).
  bool GetErrors(std::uint16_t* errors, std::string* error);

  // What the last Open's USB setup did (ok = set and verified).
  const MaestroUsbSetupResult& usb_setup() const { return usb_setup_; }

 private:
  bool Fail(const std::string& reason, std::string* error) const;
  bool Write(const std::uint8_t* bytes, std::size_t count, std::string* error);
  // Reads exactly `count` bytes within answer_timeout_ms.
  bool ReadAnswer(std::uint8_t* bytes, std::size_t count, const std::string& what,
                  std::string* error);
  // The channels' mapping inside the Maestro's own Min/Max (read over USB), else why not.
  bool CheckChannelRanges(std::string* error) const;
  bool SetSpeedAndAcceleration(std::string* error);
  void Close();

  MaestroServoDriverOptions options_;
  std::unique_ptr<MaestroUsbPort> usb_;
  MaestroUsbSetupResult usb_setup_;
  int fd_ = -1;
};

}  // namespace kapfix::agent
