// The Agent restarted (issue 14): a new boot id, and back with the operator's settings,
// fixating the slice it held; fresh when told not to resume or when the stored record is
// corrupt.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "agent/agent.hpp"
#include "agent/config_file/agent_config_file.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/heartbeat.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "tests/agent/kite_config_in.hpp"
#include "tests/link/link_test_support.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

namespace fs = std::filesystem;
using kapfix::testing::TempDir;

// An agent flying in simulation, as fast as the machine allows, until it goes.
class RunningAgent {
 public:
  RunningAgent(const AgentConfig& config, AgentOptions options)
      : agent_(config, options), thread_([this] { agent_.Run(); }) {}
  ~RunningAgent() {
    agent_.Stop();
    thread_.join();
  }
  RunningAgent(const RunningAgent&) = delete;
  RunningAgent& operator=(const RunningAgent&) = delete;
  Agent& agent() { return agent_; }

 private:
  Agent agent_;
  std::thread thread_;
};

AgentOptions Simulated(bool resume = true) {
  AgentOptions options;
  options.simulate = true;
  options.real_time = false;
  options.resume = resume;
  return options;
}

// The first published state that `wanted` accepts, among the next few (states come on every
// change and about once a second).
std::optional<kapfix::v1::AgentState> WaitForState(
    kapfix::testing::RawSubscriber& subscriber,
    const std::function<bool(const kapfix::v1::AgentState&)>& wanted) {
  for (int i = 0; i < 30; ++i) {
    const auto payload = subscriber.Next("state");
    if (!payload) return std::nullopt;
    kapfix::v1::AgentState state;
    if (state.ParseFromString(*payload) && wanted(state)) return state;
  }
  return std::nullopt;
}

bool Send(Agent& agent, kapfix::v1::Command command, std::uint64_t sequence) {
  kapfix::testing::RawStation station(agent.command_endpoint());
  // An empty agent id addresses whichever agent answers.
  kapfix::v1::Stamp(command.mutable_header(), "", sequence);
  const auto reply = station.Exchange(command);
  EXPECT_TRUE(reply.has_value());
  EXPECT_TRUE(reply && reply->ok()) << (reply ? reply->reason() : "no reply");
  return reply && reply->ok();
}

// First run: the operator sets P to 0.6 and fixates slice 3; then the agent goes.
void FlyAndSetGainsAndSlice(const AgentConfig& config) {
  RunningAgent running(config, Simulated());
  kapfix::testing::RawSubscriber states(running.agent().stream_endpoint(), {"heartbeat", "state"});
  ASSERT_TRUE(states.Ready());
  kapfix::v1::Command gains;
  gains.mutable_set_gains()->set_p(0.6F);
  ASSERT_TRUE(Send(running.agent(), gains, 1));
  kapfix::v1::Command slice;
  slice.set_select_slice(3);
  ASSERT_TRUE(Send(running.agent(), slice, 2));
  const auto fixating = WaitForState(states, [](const kapfix::v1::AgentState& s) {
    return s.mode() == kapfix::v1::MODE_FIXATE && s.slice() == 3 &&
           std::abs(s.gains().p() - 0.6F) < 1e-6F;
  });
  ASSERT_TRUE(fixating.has_value()) << "the first run never fixated slice 3 with P 0.6";
  EXPECT_FALSE(fixating->resumed());
  running.agent().FlushResumeRecord();
}

TEST(AgentResumeTest, ARestartedAgentFixatesItsSliceAgainWithTheOperatorsGains) {
  TempDir base;
  const AgentConfig config = KiteConfigIn(base.path());
  ASSERT_NE(config.gains.p(), 0.6) << "the test needs a configured P other than the operator's";
  FlyAndSetGainsAndSlice(config);

  RunningAgent restarted(config, Simulated());
  kapfix::testing::RawSubscriber states(restarted.agent().stream_endpoint(),
                                        {"heartbeat", "state"});
  ASSERT_TRUE(states.Ready());
  const auto resumed =
      WaitForState(states, [](const kapfix::v1::AgentState& s) { return s.resumed(); });
  ASSERT_TRUE(resumed.has_value()) << "the restarted agent never said it resumed";
  EXPECT_EQ(resumed->mode(), kapfix::v1::MODE_FIXATE);
  EXPECT_EQ(resumed->slice(), 3u);
  EXPECT_FLOAT_EQ(resumed->gains().p(), 0.6F);
}

TEST(AgentResumeTest, NoResumeStartsFromTheConfiguration) {
  TempDir base;
  const AgentConfig config = KiteConfigIn(base.path());
  FlyAndSetGainsAndSlice(config);

  RunningAgent fresh(config, Simulated(/*resume=*/false));
  kapfix::testing::RawSubscriber states(fresh.agent().stream_endpoint(), {"heartbeat", "state"});
  ASSERT_TRUE(states.Ready());
  const auto state = WaitForState(
      states, [](const kapfix::v1::AgentState& s) { return s.mode() == kapfix::v1::MODE_FIXATE; });
  ASSERT_TRUE(state.has_value());
  EXPECT_FALSE(state->resumed());
  EXPECT_FLOAT_EQ(state->gains().p(), static_cast<float>(config.gains.p()));
  EXPECT_EQ(state->slice(), static_cast<std::uint32_t>((config.search.slices + 1) / 2));
}

TEST(AgentResumeTest, ACorruptRecordIsSetAsideAndTheAgentStartsFresh) {
  TempDir base;
  const AgentConfig config = KiteConfigIn(base.path());
  const fs::path record = fs::path(config.state_dir) / "resume" / "resume.json";
  fs::create_directories(record.parent_path());
  std::ofstream(record) << "{\"format\": 1, \"mode\": \"fixate\", \"sli";  // cut short

  RunningAgent fresh(config, Simulated());
  kapfix::testing::RawSubscriber states(fresh.agent().stream_endpoint(), {"heartbeat", "state"});
  ASSERT_TRUE(states.Ready());
  const auto state = WaitForState(
      states, [](const kapfix::v1::AgentState& s) { return s.mode() == kapfix::v1::MODE_FIXATE; });
  ASSERT_TRUE(state.has_value());
  EXPECT_FALSE(state->resumed());
  EXPECT_FLOAT_EQ(state->gains().p(), static_cast<float>(config.gains.p()));
  EXPECT_TRUE(fs::exists(record.string() + ".bad"));
}

// Every message of one start carries one boot id; the next start another.
TEST(AgentResumeTest, EachStartHasItsOwnBootIdOnEverythingItSends) {
  TempDir base;
  const AgentConfig config = KiteConfigIn(base.path());
  std::uint64_t first = 0;
  {
    RunningAgent running(config, Simulated());
    first = running.agent().boot_id();
    EXPECT_NE(first, 0u);
    kapfix::testing::RawSubscriber streams(running.agent().stream_endpoint(),
                                           {"heartbeat", "state", "telemetry"});
    ASSERT_TRUE(streams.Ready());
    kapfix::v1::Heartbeat heartbeat;
    kapfix::v1::AgentState state;
    kapfix::v1::Telemetry telemetry;
    const auto h = streams.Next("heartbeat");
    ASSERT_TRUE(h && heartbeat.ParseFromString(*h));
    const auto s = streams.Next("state");
    ASSERT_TRUE(s && state.ParseFromString(*s));
    const auto t = streams.Next("telemetry");
    ASSERT_TRUE(t && telemetry.ParseFromString(*t));
    EXPECT_EQ(heartbeat.header().boot_id(), first);
    EXPECT_EQ(state.header().boot_id(), first);
    EXPECT_EQ(telemetry.header().boot_id(), first);
    kapfix::testing::RawStation station(running.agent().command_endpoint());
    kapfix::v1::Command request;
    request.mutable_request_state();
    kapfix::v1::Stamp(request.mutable_header(), config.agent_id, 1);
    const auto reply = station.Exchange(request);
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(reply->header().boot_id(), first);
  }
  RunningAgent restarted(config, Simulated());
  EXPECT_NE(restarted.agent().boot_id(), 0u);
  EXPECT_NE(restarted.agent().boot_id(), first);
  kapfix::testing::RawSubscriber streams(restarted.agent().stream_endpoint(), {"heartbeat"});
  ASSERT_TRUE(streams.Ready());
  kapfix::v1::Heartbeat heartbeat;
  const auto h = streams.Next("heartbeat");
  ASSERT_TRUE(h && heartbeat.ParseFromString(*h));
  EXPECT_EQ(heartbeat.header().boot_id(), restarted.agent().boot_id());
}

}  // namespace
}  // namespace kapfix::agent
