// The agent's start-up on a fresh install (issue 10): what is missing is waited for, not a
// reason to exit.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "agent/agent.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/curve_key_file.hpp"
#include "link/curve_key_pair.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::agent {
namespace {

namespace fs = std::filesystem;

// A TCP port free on this machine just now (the kernel's pick for port 0).
int FreePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof(address);
  int port = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0) {
    port = ntohs(address.sin_port);
  }
  ::close(fd);
  return port;
}

class AgentStartupTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("kapfix-startup-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    config_ = BuiltInConfig(MotionKind::kKite);
    config_.simulation.scene = std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg";
    config_.photos.dir = (dir_ / "photos").string();
    config_.state_dir = (dir_ / "state").string();
    config_.link.command_address = "ipc://" + (dir_ / "cmd").string();
    config_.link.stream_address = "ipc://" + (dir_ / "stream").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
  AgentConfig config_;
};

// What the package's postinst leaves: the agent's key and an empty station list. The agent
// starts, on this machine only, instead of refusing a list no station is in yet.
TEST_F(AgentStartupTest, EmptyStationListServesThisMachineOnly) {
  std::string error;
  ASSERT_TRUE(kapfix::link::WriteSecretKeyFile(
      dir_ / "agent.key", kapfix::link::GenerateCurveKeyPair(), "agent", false, &error))
      << error;
  std::ofstream(dir_ / "authorized_keys").close();
  config_.link.curve_secret_key_file = (dir_ / "agent.key").string();
  config_.link.curve_authorized_keys_file = (dir_ / "authorized_keys").string();
  config_.link.command_address = "tcp://*:" + std::to_string(FreePort());
  config_.link.stream_address = "tcp://*:" + std::to_string(FreePort());
  Agent agent(config_, {.simulate = true, .real_time = false, .frames = 1});
  EXPECT_TRUE(agent.command_endpoint().starts_with("tcp://127.0.0.1:")) << agent.command_endpoint();
  EXPECT_TRUE(agent.stream_endpoint().starts_with("tcp://127.0.0.1:")) << agent.stream_endpoint();
}

// No camera and no servo controller at start: the agent is built (it will retry both), and
// a Stop ends its run cleanly, with no frame processed.
TEST_F(AgentStartupTest, MissingDevicesAreWaitedForNotAnError) {
  config_.camera.backend = CameraBackend::kV4l2;
  config_.camera.device = "/dev/video97";
  config_.servo.backend = ServoBackend::kMaestro;
  config_.servo.device = "/dev/ttyACM97";
  std::unique_ptr<Agent> agent;
  ASSERT_NO_THROW(agent = std::make_unique<Agent>(config_, AgentOptions{}));
  EXPECT_FALSE(agent->simulated());
  // What is missing is in the state a station gets, with the device's own reason.
  kapfix::testing::RawStation station(agent->command_endpoint());
  kapfix::v1::Command request;
  request.mutable_request_state();
  kapfix::v1::Stamp(request.mutable_header(), config_.agent_id, 1);
  const auto reply = station.Exchange(request);
  ASSERT_TRUE(reply.has_value());
  const kapfix::v1::AgentState& state = reply->state();
  EXPECT_EQ(state.camera_health().status(), kapfix::v1::DEVICE_WAITING);
  EXPECT_NE(state.camera_health().reason().find("/dev/video97"), std::string::npos)
      << state.camera_health().reason();
  EXPECT_EQ(state.servo_health().status(), kapfix::v1::DEVICE_WAITING);
  EXPECT_NE(state.servo_health().reason().find("/dev/ttyACM97"), std::string::npos)
      << state.servo_health().reason();
  agent->Stop();
  const PipelineStats stats = agent->Run();
  EXPECT_EQ(stats.processed, 0u);
}

}  // namespace
}  // namespace kapfix::agent
