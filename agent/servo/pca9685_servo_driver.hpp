#pragma once

#include <cstdint>
#include <string>

#include "agent/servo/servo_channel_mapping.hpp"
#include "agent/servo/servo_driver.hpp"

namespace kapfix::agent {

struct Pca9685ServoDriverOptions {
  std::string device = "/dev/i2c-1";  // Linux I2C bus (i2c-dev module)
  int address = 0x40;                 // 7-bit address: 0x40 + A5…A0 jumpers
  double pwm_hz = 50;                 // [Hz] servo frame rate; analogue servos want 50
  // [Hz] the chip's internal oscillator is 25 MHz ± a few %: measure the output period once
  // and set this to 25e6 · 20 ms / measured period if the angles must be exact.
  double oscillator_hz = 25e6;
  ServoChannelMapping pan{.channel = 0};
  ServoChannelMapping tilt{.channel = 1};

  // Also: the widest pulse must fit in one PWM period.
  bool IsValid(std::string* error) const;
};

// A PCA9685 16-channel PWM board on a Linux I2C bus (ioctl I2C_SLAVE, then plain writes).
// Open puts the chip to sleep, sets PRE_SCALE for pwm_hz, wakes it with auto-increment and
// reads PRE_SCALE back to check that a PCA9685 answers. Each SetAngle is one 5-byte write to
// the channel's LEDn_ON/OFF registers (pca9685_registers.hpp holds the arithmetic).
//
// If the agent dies the chip keeps sending the last pulses, so the servos hold their last
// position: the PCA9685 has no command timeout (unlike the Maestro), and the agent's
// watchdog parks the servos only while the agent runs.
class Pca9685ServoDriver : public ServoDriver {
 public:
  explicit Pca9685ServoDriver(Pca9685ServoDriverOptions options);
  ~Pca9685ServoDriver() override;
  Pca9685ServoDriver(const Pca9685ServoDriver&) = delete;
  Pca9685ServoDriver& operator=(const Pca9685ServoDriver&) = delete;

  bool Open(std::string* error) override;
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override;
  // 0 deg (the centre pulse) on both channels.
  bool Park(std::string* error) override;
  // Reads the channel's LEDn_ON/OFF registers back (the chip keeps its pulses through an I2C
  // outage) and maps the pulse to an angle; false for a channel that is off.
  bool ReadAngle(ServoAxis axis, double* deg, std::string* error) override;
  std::string Describe() const override;

 private:
  bool Fail(const std::string& reason, std::string* error) const;
  bool WriteBytes(const std::uint8_t* bytes, std::size_t count, std::string* error);
  bool ReadRegister(std::uint8_t reg, std::uint8_t* value, std::string* error);
  void Close();

  Pca9685ServoDriverOptions options_;
  int prescale_ = 0;
  int fd_ = -1;
};

}  // namespace kapfix::agent
