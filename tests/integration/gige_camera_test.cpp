// The agent flies from a camera that speaks the real GigE Vision protocol: Debian's
// arv-fake-gv-camera-0.8 (aravis-tools) on 127.0.0.1, opened by the agent with
// `--camera aravis:127.0.0.1`; its servos are a Maestro played on a pseudo-terminal
// (`--servos maestro:/dev/pts/N`): Get Errors and Get Position answered, every Set Target
// recorded. Issue 10. Waits on log lines and Maestro bytes, with generous deadlines that only
// bound a failure.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "agent/capture/aravis_frame_source.hpp"
#include "kapfix/v1/state.pb.h"
#include "tests/integration/child_process.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;
using std::chrono::steady_clock;

constexpr const char* kFakeCamera = "/usr/bin/arv-fake-gv-camera-0.8";

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Waits until `path` contains `needle` (true) or `deadline` passes (false).
bool WaitForText(const fs::path& path, const std::string& needle, steady_clock::duration within) {
  const auto deadline = steady_clock::now() + within;
  while (steady_clock::now() < deadline) {
    if (ReadFile(path).find(needle) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// A Maestro on the master side of a pseudo-terminal, answering on its own thread.
class PtyMaestro {
 public:
  struct Target {
    int channel;
    int quarter_us;
  };

  PtyMaestro() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ >= 0 && ::grantpt(master_) == 0 && ::unlockpt(master_) == 0) {
      if (const char* name = ::ptsname(master_)) path_ = name;
    }
    // Keep the terminal side open here too, so the master never sees a hang-up between the
    // agent's opens.
    if (!path_.empty()) slave_ = ::open(path_.c_str(), O_RDWR | O_NOCTTY);
    thread_ = std::thread([this] { Serve(); });
  }
  ~PtyMaestro() {
    stop_ = true;
    thread_.join();
    if (slave_ >= 0) ::close(slave_);
    if (master_ >= 0) ::close(master_);
  }
  const std::string& path() const { return path_; }
  std::vector<Target> targets() const {
    std::lock_guard lock(mutex_);
    return targets_;
  }

 private:
  bool ReadByte(std::uint8_t* byte) {
    while (!stop_) {
      pollfd p{master_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0 || !(p.revents & POLLIN)) continue;
      if (::read(master_, byte, 1) == 1) return true;
    }
    return false;
  }
  void Answer(std::uint8_t low, std::uint8_t high) {
    const std::uint8_t bytes[2] = {low, high};
    (void)!::write(master_, bytes, 2);
  }
  void Serve() {
    std::uint8_t command = 0;
    while (ReadByte(&command)) {
      std::uint8_t data[3] = {0, 0, 0};
      if (command == 0xA1) {
        Answer(0, 0);  // Get Errors: none
      } else if (command == 0x90) {
        if (!ReadByte(&data[0])) return;
        Answer(0x70, 0x17);  // Get Position: 6000 quarter-µs, the centre
      } else if (command == 0x84 || command == 0x87 || command == 0x89) {
        for (std::uint8_t& b : data) {
          if (!ReadByte(&b)) return;
        }
        if (command == 0x84) {
          std::lock_guard lock(mutex_);
          targets_.push_back({data[0], data[1] | (data[2] << 7)});
        }
      }
    }
  }

  int master_ = -1;
  int slave_ = -1;
  std::string path_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::vector<Target> targets_;
  std::thread thread_;
};

class GigECameraTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kFakeCamera)) GTEST_SKIP() << kFakeCamera << " missing (aravis-tools)";
    ASSERT_FALSE(maestro_.path().empty()) << "no pseudo-terminal";
    folder_ = fs::temp_directory_path() / ("kapfix-gige-" + std::to_string(::getpid()));
    fs::create_directories(folder_);
  }
  void TearDown() override {
    agent_.reset();
    camera_.reset();
    fs::remove_all(folder_);
  }
  void StartCamera(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{kFakeCamera, "-i", "127.0.0.1"};
    args.insert(args.end(), extra.begin(), extra.end());
    camera_ = std::make_unique<ChildProcess>(args, folder_ / "camera.out", folder_ / "camera.err");
  }
  std::vector<std::string> AgentArgs(const std::vector<std::string>& extra) {
    UnusedPort command;
    UnusedPort stream;
    command_port_ = command.port();
    stream_port_ = stream.port();
    std::vector<std::string> args{KAPFIX_AGENT,
                                  "--camera",
                                  "aravis:127.0.0.1",
                                  "--servos",
                                  "maestro:" + maestro_.path(),
                                  "--command-address",
                                  "tcp://127.0.0.1:" + std::to_string(command.port()),
                                  "--stream-address",
                                  "tcp://127.0.0.1:" + std::to_string(stream.port()),
                                  "--photos",
                                  (folder_ / "photos").string(),
                                  "--state-dir",
                                  (folder_ / "state").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  void StartAgent(const std::vector<std::string>& extra = {}) {
    agent_ = std::make_unique<ChildProcess>(AgentArgs(extra), folder_ / "agent.out", log());
  }
  fs::path log() const { return folder_ / "agent.err"; }
  // `kapfix-ctl status` against the agent started last.
  ProcessOutcome CtlStatus() const {
    return RunProcess(std::string(KAPFIX_CTL) + " --agent 127.0.0.1 --command-port " +
                          std::to_string(command_port_) + " --stream-port " +
                          std::to_string(stream_port_) + " --timeout 5000 status",
                      folder_ / "ctl.err");
  }

  PtyMaestro maestro_;
  int command_port_ = 0;
  int stream_port_ = 0;
  fs::path folder_;
  std::unique_ptr<ChildProcess> camera_;
  std::unique_ptr<ChildProcess> agent_;
};

TEST_F(GigECameraTest, PreflightReadsOneFrameOfTheConfiguredSize) {
  StartCamera();
  ChildProcess preflight(AgentArgs({"--preflight"}), folder_ / "preflight.out",
                         folder_ / "preflight.err");
  const auto deadline = steady_clock::now() + seconds(60);
  while (preflight.running() && steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::string out = ReadFile(folder_ / "preflight.out");
  EXPECT_NE(out.find("PASS camera: aravis 127.0.0.1"), std::string::npos) << out;
  EXPECT_NE(out.find("one 640x480 frame"), std::string::npos) << out;
  // The settings are tried too: the fake camera has no automatic exposure, the schema's default.
  EXPECT_NE(out.find("settings not all applied: Aravis camera '127.0.0.1': auto_exposure = true: "
                     "the camera has no ExposureAuto feature"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("PASS servos: maestro " + maestro_.path()), std::string::npos) << out;
}

TEST_F(GigECameraTest, AgentFliesFromTheFakeCameraAndCommandsTheServos) {
  StartCamera();
  StartAgent({"--frames", "60"});
  const auto deadline = steady_clock::now() + seconds(90);
  while (agent_->running() && steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(agent_->Stop(SIGTERM), 0) << ReadFile(log());
  EXPECT_NE(ReadFile(log()).find("processed 60 frames"), std::string::npos) << ReadFile(log());
  EXPECT_GE(maestro_.targets().size(), 2u * 60 - 4);  // pan and tilt each frame
}

// The camera dies mid-flight and comes back: the agent reconnects on its own; meanwhile it
// sends the servos nothing (they hold), and afterwards it resumes.
TEST_F(GigECameraTest, KilledAndRestartedCameraIsReconnectedWhileTheServosHold) {
  StartCamera();
  StartAgent();
  const auto flying = steady_clock::now() + seconds(60);
  while (maestro_.targets().size() < 60 && steady_clock::now() < flying) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GE(maestro_.targets().size(), 60u) << ReadFile(log());
  camera_->Stop(SIGKILL);
  ASSERT_TRUE(WaitForText(log(), "camera lost", seconds(30))) << ReadFile(log());
  const std::size_t at_loss = maestro_.targets().size();
  std::this_thread::sleep_for(std::chrono::seconds(1));  // an outage, long enough to notice
  const std::size_t before_back = maestro_.targets().size();
  StartCamera();
  ASSERT_TRUE(WaitForText(log(), "camera back after", seconds(60))) << ReadFile(log());
  // Held: nothing sent during the outage (one frame already taken may finish: 2 targets).
  EXPECT_LE(before_back - at_loss, 2u);
  const auto resumed = steady_clock::now() + seconds(60);
  while (maestro_.targets().size() < before_back + 20 && steady_clock::now() < resumed) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GE(maestro_.targets().size(), before_back + 20) << ReadFile(log());
  EXPECT_EQ(agent_->Stop(SIGTERM), 0) << ReadFile(log());
  EXPECT_NE(ReadFile(log()).find("servos parked"), std::string::npos) << ReadFile(log());
}

// The next AgentState from `station` whose camera health is `status`, within `within`
// (the agent republishes its state about once a second); std::nullopt if none came.
std::optional<kapfix::v1::AgentState> NextStateWithCamera(RawSubscriber& station,
                                                          kapfix::v1::DeviceStatus status,
                                                          steady_clock::duration within) {
  const auto deadline = steady_clock::now() + within;
  while (steady_clock::now() < deadline) {
    const auto payload = station.Next("state");
    kapfix::v1::AgentState state;
    if (payload && state.ParseFromString(*payload) && state.camera_health().status() == status) {
      return state;
    }
  }
  return std::nullopt;
}

// Start-up that waits for hardware, as a station sees it: no camera when the agent starts, so
// its state over the link says the camera is waiting (and why) and kapfix-ctl status prints
// it; the camera is switched on, and the state and kapfix-ctl say it is there.
TEST_F(GigECameraTest, ACameraMissingAtStartIsReportedWaitingThenOkOverTheLink) {
  StartAgent();
  RawSubscriber station("tcp://127.0.0.1:" + std::to_string(stream_port_), {"heartbeat", "state"});
  const auto up = steady_clock::now() + seconds(60);
  bool ready = false;
  while (!ready && agent_->running() && steady_clock::now() < up) ready = station.Ready();
  ASSERT_TRUE(ready) << ReadFile(log());

  const auto waiting = NextStateWithCamera(station, kapfix::v1::DEVICE_WAITING, seconds(30));
  ASSERT_TRUE(waiting.has_value()) << ReadFile(log());
  EXPECT_NE(waiting->camera_health().reason().find("127.0.0.1"), std::string::npos)
      << waiting->camera_health().reason();
  EXPECT_EQ(waiting->servo_health().status(), kapfix::v1::DEVICE_OK);
  const ProcessOutcome before = CtlStatus();
  EXPECT_EQ(before.exit_code, 0) << before.err;
  EXPECT_NE(before.out.find("camera: waiting reason="), std::string::npos) << before.out;
  EXPECT_NE(before.out.find("servos: ok"), std::string::npos) << before.out;

  StartCamera();
  const auto ok = NextStateWithCamera(station, kapfix::v1::DEVICE_OK, seconds(60));
  ASSERT_TRUE(ok.has_value()) << ReadFile(log());
  EXPECT_TRUE(ok->camera_health().reason().empty()) << ok->camera_health().reason();
  EXPECT_GT(ok->version(), waiting->version());
  const ProcessOutcome after = CtlStatus();
  EXPECT_EQ(after.exit_code, 0) << after.err;
  EXPECT_NE(after.out.find("camera: ok\n"), std::string::npos) << after.out;
  EXPECT_EQ(agent_->Stop(SIGTERM), 0) << ReadFile(log());
}

// The camera settings message reaches a GigE Vision camera as GVCP register writes: the fake
// camera draws its frames with a scale of 1 + gain + log10(exposure / 10 ms), so 1000 µs makes
// them black. A few frames were filled before the change: counted, not timed.
TEST_F(GigECameraTest, AnExposureInTheSettingsMessageReachesTheCamera) {
  if (!agent::AravisFrameSource::Available()) GTEST_SKIP() << "built without Aravis";
  StartCamera();
  agent::AravisFrameSourceOptions options;
  options.camera_id = "127.0.0.1";
  agent::AravisFrameSource source(options);
  std::string error;
  const auto deadline = steady_clock::now() + seconds(60);  // the camera process starting
  bool open = source.Open(&error);
  while (!open && steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    open = source.Open(&error);
  }
  ASSERT_TRUE(open) << error;
  agent::CapturedFrame frame;
  ASSERT_TRUE(source.Grab(&frame, &error)) << error;
  ASSERT_GT(cv::mean(frame.image)[0], 50) << "the fake camera's frames at its default exposure";
  kapfix::v1::CameraSettings settings;
  settings.set_exposure_us(1000);
  ASSERT_TRUE(source.Apply(settings, &error)) << error;
  bool dark = false;
  for (int i = 0; i < 16 && !dark; ++i) {
    ASSERT_TRUE(source.Grab(&frame, &error)) << error;
    dark = cv::mean(frame.image)[0] < 1;
  }
  EXPECT_TRUE(dark) << "no black frame in 16 after the exposure was set to 1000 µs";
}

// 0.1 % of the stream's packets lost: some frames are incomplete and skipped, the flight goes
// on.
TEST_F(GigECameraTest, AgentFliesThroughOccasionalPacketLoss) {
  StartCamera({"-r", "1"});
  StartAgent({"--frames", "60"});
  const auto deadline = steady_clock::now() + seconds(120);
  while (agent_->running() && steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(agent_->Stop(SIGTERM), 0) << ReadFile(log());
  EXPECT_NE(ReadFile(log()).find("processed 60 frames"), std::string::npos) << ReadFile(log());
}

// 2 % lost: the fake camera does not resend, so with ~220 packets a frame hardly any frame
// arrives whole. The agent says the camera is lost and keeps reconnecting; it does not exit.
TEST_F(GigECameraTest, HeavyPacketLossIsACameraOutageNotAnExit) {
  StartCamera({"-r", "20"});
  StartAgent();
  ASSERT_TRUE(WaitForText(log(), "incomplete); the servos hold, reconnecting", seconds(60)))
      << ReadFile(log());
  ASSERT_TRUE(WaitForText(log(), "camera back after", seconds(60))) << ReadFile(log());
  EXPECT_TRUE(agent_->running());
  EXPECT_EQ(agent_->Stop(SIGTERM), 0) << ReadFile(log());
}

}  // namespace
}  // namespace kapfix::testing
