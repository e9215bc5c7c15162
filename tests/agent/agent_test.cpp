// The Agent as wired by kapfix-agent: a restart with what an earlier run stored.
#include "agent/agent.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "agent/config_file/agent_config_file.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "tests/agent/kite_config_in.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::agent {
namespace {

namespace fs = std::filesystem;

TEST(AgentTest, RestartedWithAStoredCalibrationOfAnOpticalLensItAcceptsSettingsCommands) {
  const fs::path base =
      fs::temp_directory_path() / ("kapfix_agent_restart_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const AgentConfig config = KiteConfigIn(base);
  ASSERT_GT(config.active_lens().focal_mm, 0) << "the test needs a lens defined by its optics";
  // What an earlier run's calibration left in the state folder.
  const CalibrationStore store(fs::path(config.state_dir) / "calibration");
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile(config.lens);
  report.set_finished(true);
  store.Save(config.lens, {.pan_deg_per_px = 0.15, .tilt_deg_per_px = 0.14}, report);

  Agent agent(config, {.simulate = true, .real_time = false, .frames = 1});
  kapfix::testing::RawStation station(agent.command_endpoint());
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_p(0.75F);
  kapfix::v1::Stamp(command.mutable_header(), config.agent_id, 1);
  const auto reply = station.Exchange(command);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok()) << reply->reason();

  kapfix::v1::Command request;
  request.mutable_request_state();
  kapfix::v1::Stamp(request.mutable_header(), config.agent_id, 2);
  const auto state = station.Exchange(request);
  ASSERT_TRUE(state.has_value());
  EXPECT_FLOAT_EQ(state->state().gains().p(), 0.75F);
  fs::remove_all(base);
}

// A state lost on the link heals by itself: a station that subscribes after the last change
// still gets the agent's state, without asking for it (StateRepublisher, about 1 Hz).
TEST(AgentTest, AStationThatSubscribesLateGetsTheStateWithoutAsking) {
  const fs::path base =
      fs::temp_directory_path() / ("kapfix_agent_late_" + std::to_string(::getpid()));
  fs::remove_all(base);
  const AgentConfig config = KiteConfigIn(base);
  Agent agent(config, {.simulate = true, .real_time = false, .frames = 1});
  kapfix::testing::RawSubscriber station(agent.stream_endpoint(), {"heartbeat", "state"});
  ASSERT_TRUE(station.Ready());
  const auto payload = station.Next("state");
  ASSERT_TRUE(payload.has_value()) << "no state within the wait";
  kapfix::v1::AgentState state;
  ASSERT_TRUE(state.ParseFromString(*payload));
  EXPECT_EQ(state.header().agent_id(), config.agent_id);
  EXPECT_GT(state.version(), 0u);
  fs::remove_all(base);
}

}  // namespace
}  // namespace kapfix::agent
