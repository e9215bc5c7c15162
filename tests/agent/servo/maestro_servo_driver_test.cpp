#include "agent/servo/maestro_servo_driver.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "agent/servo/maestro_protocol.hpp"
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
  // The Maestro unplugged: the master goes away and the terminal side hangs up (EIO).
  void Unplug() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
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

// Opens `driver` while playing the Maestro: waits for Get Errors and answers `errors` (only
// once its serial mode, set over `usb`, is USB Dual Port, as a real one), then takes every
// byte Open sends after it (speed and acceleration limits). Returns the bytes sent.
std::vector<std::uint8_t> OpenAnswering(PseudoTerminal& pty, MaestroServoDriver& driver,
                                        std::vector<std::uint8_t> errors, std::string* error,
                                        bool* opened,
                                        const FakeMaestroUsbPort::State* usb = nullptr) {
  std::vector<std::uint8_t> seen;
  std::atomic<bool> done{false};
  std::thread maestro([&] {
    seen = pty.Read(1, 3000);
    const bool listening =
        !usb || usb->eeprom.at(maestro::kParameterSerialMode) == maestro::kSerialModeUsbDualPort;
    if (seen == std::vector<std::uint8_t>{0xA1} && listening) pty.Write(errors);
    while (!done) {
      const auto more = pty.Read(64, 20);
      seen.insert(seen.end(), more.begin(), more.end());
    }
    const auto rest = pty.Read(64, 20);
    seen.insert(seen.end(), rest.begin(), rest.end());
  });
  *opened = driver.Open(error);
  done = true;
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
  ASSERT_FALSE(sent.empty());
  EXPECT_EQ(sent.front(), 0xA1);
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
  usb_.eeprom[maestro::kParameterSerialMode] = maestro::kSerialModeUsbDualPort;
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

TEST_F(MaestroServoDriverTest, FactoryFreshMaestroIsSetToUsbDualPortAndThenAnswers) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  EXPECT_TRUE(opened) << error;
  EXPECT_EQ(usb_.eeprom[maestro::kParameterSerialMode], maestro::kSerialModeUsbDualPort);
  EXPECT_NE(driver.usb_setup().message.find("serial mode UART, detect baud rate (2) → USB Dual "
                                            "Port (0)"),
            std::string::npos)
      << driver.usb_setup().message;
}

TEST_F(MaestroServoDriverTest, FactoryFreshMaestroWithoutUsbSaysWhyItDoesNotAnswer) {
  usb_.open_error = "no Maestro found on USB";
  MaestroServoDriverOptions options = Options(pty_.path());
  options.answer_timeout_ms = 50;
  MaestroServoDriver driver = Driver(options);
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  EXPECT_FALSE(opened);
  EXPECT_NE(error.find("USB Dual Port"), std::string::npos) << error;
  EXPECT_NE(error.find("no Maestro found on USB"), std::string::npos) << error;
}

TEST_F(MaestroServoDriverTest, MappingBeyondTheChannelsOwnMinMaxIsRefusedWithTheValuesToSet) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.pan.min_us = 900;  // factory Min is 992 µs
  options.pan.max_us = 2100;
  MaestroServoDriver driver = Driver(options);
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  EXPECT_FALSE(opened);
  EXPECT_NE(error.find("992…2000 µs"), std::string::npos) << error;
  EXPECT_NE(error.find("Min ≤ 896 µs and Max ≥ 2112 µs"), std::string::npos) << error;
}

TEST_F(MaestroServoDriverTest, OpenSetsEachChannelsSpeedAndAccelerationFromTheRateLimit) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.pan_max_rate_deg_per_s = 150;   // · 10 µs/deg · 4 · 0.01 = 60 [¼ µs / 10 ms]
  options.tilt_max_rate_deg_per_s = 100;  // 40
  options.acceleration_ramp_ms = 20;      // 60 · 80 / 20 = 240; 40 · 4 = 160
  MaestroServoDriver driver = Driver(options);
  std::string error;
  bool opened = false;
  const auto sent = OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  ASSERT_TRUE(opened) << error;
  EXPECT_EQ(sent, (std::vector<std::uint8_t>{0xA1, 0x87, 0x00, 60, 0, 0x89, 0x00, 0x70, 0x01, 0x87,
                                             0x05, 40, 0, 0x89, 0x05, 0x20, 0x01}));
}

TEST_F(MaestroServoDriverTest, ReadAngleAsksGetPositionAndMapsItBack) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  ASSERT_TRUE(opened) << error;
  double deg = 0;
  bool read = false;
  std::thread reader([&] { read = driver.ReadAngle(ServoAxis::kTilt, &deg, &error); });
  EXPECT_EQ(pty_.Read(2, 3000), (std::vector<std::uint8_t>{0x90, 0x05}));
  pty_.Write({0x70, 0x17});
  reader.join();
  ASSERT_TRUE(read) << error;
  // 0x1770 = 6000 quarter-µs = 1500 µs = the centre: 0 deg.
  EXPECT_DOUBLE_EQ(deg, 0);
}

// The Maestro unplugged: the terminal side reports EIO (here: the master closed, so the
// terminal hangs up) and the next command fails at once instead of blocking.
TEST_F(MaestroServoDriverTest, UnpluggedMaestroFailsTheNextCommand) {
  MaestroServoDriver driver = Driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  ASSERT_TRUE(opened) << error;
  pty_.Unplug();
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, 0, &error));
  EXPECT_NE(error.find("unplugged"), std::string::npos) << error;
}

// A wedged port: nothing reads what the driver writes, so the terminal's buffer fills and
// writes would block for ever. Each command gives up after write_timeout_ms instead.
TEST_F(MaestroServoDriverTest, WedgedPortFailsACommandWithinTheWriteTimeout) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.write_timeout_ms = 20;
  MaestroServoDriver driver = Driver(options);
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened, &usb_);
  ASSERT_TRUE(opened) << error;
  // Wedged: from here on nobody reads the master side.
  bool failed = false;
  for (int i = 0; i < 100000 && !failed; ++i) {
    failed = !driver.SetAngle(ServoAxis::kPan, 0, &error);
  }
  ASSERT_TRUE(failed) << "the pseudo-terminal never filled up";
  EXPECT_NE(error.find("did not take a command within 20 ms"), std::string::npos) << error;
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
