#include "agent/servo/maestro_servo_driver.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "tests/agent/support/fake_maestro_usb_port.hpp"

namespace kapfix::agent {
namespace {

// A pseudo-terminal stands in for the Maestro's Command Port: the driver opens the
// terminal side; the test reads the bytes it sends from the master side and answers.
class PseudoTerminal {
 public:
  PseudoTerminal() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ >= 0 && ::grantpt(master_) == 0 && ::unlockpt(master_) == 0) {
      const char* name = ::ptsname(master_);
      if (name) path_ = name;
    }
  }
  ~PseudoTerminal() {
    if (master_ >= 0) ::close(master_);
  }
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  bool ok() const { return !path_.empty(); }
  const std::string& path() const { return path_; }

  // Reads up to `count` bytes, waiting at most `timeout_ms` in all. The master reports EIO
  // while no terminal side is open; that counts as "nothing yet".
  std::vector<std::uint8_t> Read(std::size_t count, int timeout_ms) {
    std::vector<std::uint8_t> bytes;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (bytes.size() < count && std::chrono::steady_clock::now() < deadline) {
      pollfd p{master_, POLLIN, 0};
      if (::poll(&p, 1, 10) <= 0 || !(p.revents & POLLIN)) continue;
      std::uint8_t buffer[64];
      const ssize_t got = ::read(master_, buffer, std::min(sizeof(buffer), count - bytes.size()));
      if (got > 0) bytes.insert(bytes.end(), buffer, buffer + got);
    }
    return bytes;
  }
  void Write(const std::vector<std::uint8_t>& bytes) {
    ASSERT_EQ(::write(master_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }

 private:
  int master_ = -1;
  std::string path_;
};

MaestroServoDriverOptions Options(const std::string& path) {
  MaestroServoDriverOptions options;
  options.device = path;
  options.pan.channel = 0;
  options.tilt.channel = 5;
  options.answer_timeout_ms = 2000;
  return options;
}

// Opens `driver` while playing the Maestro: waits for Get Errors and answers `errors`.
// Returns the bytes the driver sent during Open.
std::vector<std::uint8_t> OpenAnswering(PseudoTerminal& pty, MaestroServoDriver& driver,
                                        std::vector<std::uint8_t> errors, std::string* error,
                                        bool* opened) {
  std::vector<std::uint8_t> seen;
  std::thread maestro([&] {
    seen = pty.Read(1, 3000);
    if (seen == std::vector<std::uint8_t>{0xA1}) pty.Write(errors);
  });
  *opened = driver.Open(error);
  maestro.join();
  return seen;
}

class MaestroServoDriverTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(pty_.ok()) << "no pseudo-terminal available"; }
  // A driver whose native USB interface is `usb_` (a Maestro at factory settings).
  MaestroServoDriver Driver(const MaestroServoDriverOptions& options) {
    return MaestroServoDriver(options, std::make_unique<FakeMaestroUsbPort>(&usb_));
  }
  PseudoTerminal pty_;
  FakeMaestroUsbPort::State usb_;
};

TEST_F(MaestroServoDriverTest, OpenSendsGetErrorsAndSucceedsOnAnAnswer) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  const auto sent = OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  EXPECT_TRUE(opened) << error;
  EXPECT_EQ(sent, (std::vector<std::uint8_t>{0xA1}));
}

TEST_F(MaestroServoDriverTest, OpenAcceptsAReportedSerialTimeout) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x20, 0x00}, &error, &opened);
  EXPECT_TRUE(opened) << error;
}

TEST_F(MaestroServoDriverTest, OpenFailsWhenNothingAnswers) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.answer_timeout_ms = 50;
  MaestroServoDriver driver = Driver(options);
  std::string error;
  EXPECT_FALSE(driver.Open(&error));
  EXPECT_NE(error.find(pty_.path()), std::string::npos) << error;
  EXPECT_NE(error.find("no answer"), std::string::npos) << error;
}

TEST_F(MaestroServoDriverTest, SetAngleWritesTheExactSetTargetBytes) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  // Tilt on channel 5, −12.5 deg at 10 µs/deg from 1500 µs: 1375 µs = 5500 quarter-µs.
  ASSERT_TRUE(driver.SetAngle(ServoAxis::kTilt, -12.5, &error)) << error;
  EXPECT_EQ(pty_.Read(4, 2000), (std::vector<std::uint8_t>{0x84, 0x05, 0x7C, 0x2A}));
}

TEST_F(MaestroServoDriverTest, ParkSendsBothChannelsToTheirCentre) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  ASSERT_TRUE(driver.Park(&error)) << error;
  EXPECT_EQ(pty_.Read(8, 2000),
            (std::vector<std::uint8_t>{0x84, 0x00, 0x70, 0x2E, 0x84, 0x05, 0x70, 0x2E}));
}

TEST_F(MaestroServoDriverTest, NonFiniteAngleIsNotSent) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, std::numeric_limits<double>::quiet_NaN(), &error));
  EXPECT_TRUE(pty_.Read(1, 100).empty());
}

TEST_F(MaestroServoDriverTest, OpenSetsTheSerialTimeoutAndTheParkPulsesOverUsb) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.serial_timeout_ms = 300;
  options.tilt_home_deg = -5;  // 1500 − 5 · 10 = 1450 µs = 5800 quarter-µs
  MaestroServoDriver driver = Driver(options);
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  EXPECT_TRUE(driver.usb_setup().ok) << driver.usb_setup().message;
  EXPECT_EQ(usb_.eeprom[6], 30);     // serial timeout [10 ms]
  EXPECT_EQ(usb_.eeprom[30], 6000);  // channel 0 (pan) home [quarter-µs]
  EXPECT_EQ(usb_.eeprom[75], 5800);  // channel 5 (tilt) home: 30 + 9 · 5
}

TEST_F(MaestroServoDriverTest, NoMaestroOnUsbIsAWarningAndTheDriverStillOpens) {
  usb_.open_error = "no Maestro found on USB";
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  EXPECT_TRUE(opened) << error;
  EXPECT_FALSE(driver.usb_setup().ok);
  EXPECT_NE(driver.usb_setup().message.find("no Maestro found on USB"), std::string::npos)
      << driver.usb_setup().message;
  ASSERT_TRUE(driver.SetAngle(ServoAxis::kPan, 0, &error)) << error;
  EXPECT_EQ(pty_.Read(4, 2000), (std::vector<std::uint8_t>{0x84, 0x00, 0x70, 0x2E}));
}

TEST_F(MaestroServoDriverTest, UsbIsNotTriedWhenTheSerialPortDoesNotAnswer) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.answer_timeout_ms = 50;
  MaestroServoDriver driver = Driver(options);
  EXPECT_FALSE(driver.Open(nullptr));
  EXPECT_EQ(usb_.opens, 0);
}

TEST(MaestroServoDriverOpenTest, MissingPortIsNamedWithTheReason) {
  MaestroServoDriverOptions options;
  options.device = "/dev/ttyACM97";
  MaestroServoDriver driver(options);
  std::string error;
  EXPECT_FALSE(driver.Open(&error));
  EXPECT_NE(error.find("/dev/ttyACM97"), std::string::npos) << error;
  EXPECT_NE(error.find("No such file"), std::string::npos) << error;
}

TEST(MaestroServoDriverOpenTest, NonTerminalIsNotASerialPort) {
  MaestroServoDriverOptions options;
  options.device = "/dev/null";
  MaestroServoDriver driver(options);
  std::string error;
  EXPECT_FALSE(driver.Open(&error));
  EXPECT_NE(error.find("not a serial port"), std::string::npos) << error;
}

TEST(MaestroServoDriverOpenTest, SetAngleBeforeOpenFails) {
  MaestroServoDriver driver(MaestroServoDriverOptions{});
  std::string error;
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, 0, &error));
  EXPECT_NE(error.find("not open"), std::string::npos) << error;
}

TEST(MaestroServoDriverOptionsTest, NonStandardBaudIsInvalid) {
  MaestroServoDriverOptions options;
  options.baud = 250000;
  EXPECT_FALSE(options.IsValid(nullptr));
}

TEST(MaestroServoDriverOptionsTest, SerialTimeoutOutsideTenMillisecondStepsIsInvalid) {
  MaestroServoDriverOptions options;
  options.serial_timeout_ms = 305;
  EXPECT_FALSE(options.IsValid(nullptr));
  options.serial_timeout_ms = 0;
  EXPECT_FALSE(options.IsValid(nullptr));
}

TEST(MaestroServoDriverOptionsTest, UsbSettingsMapTheHomeAnglesThroughTheChannels) {
  MaestroServoDriverOptions options;
  options.pan.channel = 2;
  options.pan.us_per_deg = -10;
  options.pan_home_deg = 10;  // 1500 − 100 = 1400 µs
  options.tilt.channel = 3;
  const MaestroUsbSettings settings = options.UsbSettings();
  EXPECT_EQ(settings.serial_timeout_ms, 500);
  ASSERT_EQ(settings.homes.size(), 2u);
  EXPECT_EQ(settings.homes[0].channel, 2);
  EXPECT_EQ(settings.homes[0].home_quarter_us, 5600);
  EXPECT_EQ(settings.homes[1].channel, 3);
  EXPECT_EQ(settings.homes[1].home_quarter_us, 6000);
}

TEST(MaestroServoDriverOptionsTest, SharedChannelIsInvalid) {
  MaestroServoDriverOptions options;
  options.tilt.channel = options.pan.channel;
  EXPECT_FALSE(options.IsValid(nullptr));
}

}  // namespace
}  // namespace kapfix::agent
