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
  PseudoTerminal pty_;
};

TEST_F(MaestroServoDriverTest, OpenSendsGetErrorsAndSucceedsOnAnAnswer) {
  MaestroServoDriver driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  const auto sent = OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  EXPECT_TRUE(opened) << error;
  EXPECT_EQ(sent, (std::vector<std::uint8_t>{0xA1}));
}

TEST_F(MaestroServoDriverTest, OpenAcceptsAReportedSerialTimeout) {
  MaestroServoDriver driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x20, 0x00}, &error, &opened);
  EXPECT_TRUE(opened) << error;
}

TEST_F(MaestroServoDriverTest, OpenFailsWhenNothingAnswers) {
  MaestroServoDriverOptions options = Options(pty_.path());
  options.answer_timeout_ms = 50;
  MaestroServoDriver driver(options);
  std::string error;
  EXPECT_FALSE(driver.Open(&error));
  EXPECT_NE(error.find(pty_.path()), std::string::npos) << error;
  EXPECT_NE(error.find("no answer"), std::string::npos) << error;
}

TEST_F(MaestroServoDriverTest, SetAngleWritesTheExactSetTargetBytes) {
  MaestroServoDriver driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  // Tilt on channel 5, −12.5 deg at 10 µs/deg from 1500 µs: 1375 µs = 5500 quarter-µs.
  ASSERT_TRUE(driver.SetAngle(ServoAxis::kTilt, -12.5, &error)) << error;
  EXPECT_EQ(pty_.Read(4, 2000), (std::vector<std::uint8_t>{0x84, 0x05, 0x7C, 0x2A}));
}

TEST_F(MaestroServoDriverTest, ParkSendsBothChannelsToTheirCentre) {
  MaestroServoDriver driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  ASSERT_TRUE(driver.Park(&error)) << error;
  EXPECT_EQ(pty_.Read(8, 2000),
            (std::vector<std::uint8_t>{0x84, 0x00, 0x70, 0x2E, 0x84, 0x05, 0x70, 0x2E}));
}

TEST_F(MaestroServoDriverTest, NonFiniteAngleIsNotSent) {
  MaestroServoDriver driver(Options(pty_.path()));
  std::string error;
  bool opened = false;
  OpenAnswering(pty_, driver, {0x00, 0x00}, &error, &opened);
  ASSERT_TRUE(opened) << error;
  EXPECT_FALSE(driver.SetAngle(ServoAxis::kPan, std::numeric_limits<double>::quiet_NaN(), &error));
  EXPECT_TRUE(pty_.Read(1, 100).empty());
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

TEST(MaestroServoDriverOptionsTest, SharedChannelIsInvalid) {
  MaestroServoDriverOptions options;
  options.tilt.channel = options.pan.channel;
  EXPECT_FALSE(options.IsValid(nullptr));
}

}  // namespace
}  // namespace kapfix::agent
