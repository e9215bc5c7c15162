#include "link/agent_link_client.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "kapfix/v1/telemetry.pb.h"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::link::AgentLinkClient;
using kapfix::link::AgentLinkClientOptions;
using kapfix::v1::Command;

AgentLinkClientOptions OptionsFor(const FakeAgent& agent) {
  AgentLinkClientOptions options;
  options.command_endpoint = agent.command_endpoint;
  options.stream_endpoint = agent.stream_endpoint;
  options.heartbeat_interval = std::chrono::milliseconds(50);
  options.link_timeout = std::chrono::milliseconds(300);
  return options;
}

AgentLinkClientOptions OptionsForPort(int port) {
  AgentLinkClientOptions options;
  options.command_endpoint = "tcp://127.0.0.1:" + std::to_string(port);
  options.stream_endpoint = "tcp://127.0.0.1:" + std::to_string(port);
  options.heartbeat_interval = std::chrono::milliseconds(50);
  options.link_timeout = std::chrono::milliseconds(300);
  return options;
}

Command RequestState() {
  Command command;
  command.mutable_request_state();
  return command;
}

TEST(AgentLinkClientTest, RequestReturnsTheAgentsReply) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  client.Start();
  const auto reply = client.Request(RequestState(), kWait);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok()) << reply->reason();
  EXPECT_EQ(reply->state().frame_width_px(), 640U);
}

TEST(AgentLinkClientTest, RequestsCarryIncreasingSequenceNumbersAndTheProtocolVersion) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  client.Start();
  ASSERT_TRUE(client.Request(RequestState(), kWait).has_value());
  ASSERT_TRUE(client.Request(RequestState(), kWait).has_value());
  const auto commands = agent.control.commands();
  ASSERT_EQ(commands.size(), 2U);
  EXPECT_EQ(commands[0].header().sequence(), 1U);
  EXPECT_EQ(commands[1].header().sequence(), 2U);
  EXPECT_EQ(commands[1].header().protocol_version(), kapfix::v1::kProtocolVersion);
}

TEST(AgentLinkClientTest, RefusalArrivesAsAReplyWithItsReason) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  client.Start();
  Command command;
  command.set_select_slice(0);
  const auto reply = client.Request(command, kWait);
  ASSERT_TRUE(reply.has_value());
  EXPECT_FALSE(reply->ok());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
}

TEST(AgentLinkClientTest, RequestTimesOutWhenNothingListens) {
  UnusedPort port;
  AgentLinkClient client(OptionsForPort(port.port()));
  client.Start();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(client.Request(RequestState(), std::chrono::milliseconds(200)).has_value());
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_GE(took, std::chrono::milliseconds(190));
  EXPECT_LT(took, std::chrono::milliseconds(1000));
}

TEST(AgentLinkClientTest, CommandNotSentBeforeItsDeadlineIsNeverSentLater) {
  // A servo command delivered minutes after the operator gave up would be dangerous.
  UnusedPort port;
  AgentLinkClient client(OptionsForPort(port.port()));
  client.Start();
  EXPECT_FALSE(client.Request(RequestState(), std::chrono::milliseconds(100)).has_value());
  port.Release();
  auto server_options = TestServerOptions();
  server_options.bind_endpoint = "tcp://127.0.0.1:" + std::to_string(port.port());
  FakeAgentControl control;
  kapfix::agent::CommandServer server(control, server_options);
  server.Start();
  ASSERT_TRUE(WaitFor([&] { return server.counters().heartbeats_echoed > 0; }))
      << "the client never connected";
  EXPECT_TRUE(control.commands().empty());
}

TEST(AgentLinkClientTest, HandlerReceivesEveryTelemetryInOrder) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  std::mutex mutex;
  std::vector<std::uint64_t> frames;
  client.OnMessage("telemetry", [&](const google::protobuf::Message& message) {
    const std::lock_guard lock(mutex);
    frames.push_back(static_cast<const kapfix::v1::Telemetry&>(message).frame_number());
  });
  client.Start();
  ASSERT_TRUE(client.WaitForStreams(kWait));
  for (std::uint64_t i = 0; i < 100; ++i) {
    kapfix::v1::Telemetry telemetry;
    telemetry.set_frame_number(i);
    agent.publisher.Publish(telemetry);
  }
  ASSERT_TRUE(WaitFor([&] {
    const std::lock_guard lock(mutex);
    return frames.size() >= 100;
  }));
  const std::lock_guard lock(mutex);
  for (std::uint64_t i = 0; i < 100; ++i) EXPECT_EQ(frames[i], i);
  EXPECT_EQ(client.Status().sequence_gaps, 0U);
}

TEST(AgentLinkClientTest, RawHandlerSeesEveryTopic) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  std::mutex mutex;
  std::vector<std::string> topics;
  client.OnRawMessage([&](std::string_view topic, std::string_view) {
    const std::lock_guard lock(mutex);
    topics.emplace_back(topic);
  });
  client.Start();
  ASSERT_TRUE(client.WaitForStreams(kWait));
  agent.publisher.Publish(kapfix::v1::Telemetry());
  ASSERT_TRUE(WaitFor([&] {
    const std::lock_guard lock(mutex);
    return std::find(topics.begin(), topics.end(), "telemetry") != topics.end();
  }));
  const std::lock_guard lock(mutex);
  EXPECT_NE(std::find(topics.begin(), topics.end(), "heartbeat"), topics.end());
}

TEST(AgentLinkClientTest, LinkComesUpAndReportsTheHeartbeatLatency) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  client.Start();
  ASSERT_TRUE(WaitFor([&] { return client.Status().up && client.Status().latency_us >= 0; }));
  const auto status = client.Status();
  EXPECT_EQ(status.agent_id, kAgentId);
  EXPECT_LT(status.latency_us, 1'000'000);  // loopback: far below a second
}

TEST(AgentLinkClientTest, LinkGoesDownWhenTheAgentStops) {
  auto agent = std::make_unique<FakeAgent>();
  AgentLinkClient client(OptionsFor(*agent));
  std::promise<void> down;
  std::atomic<bool> was_up{false};
  client.OnLinkChange([&](bool up) {
    if (up) was_up.store(true);
    if (!up && was_up.exchange(false)) down.set_value();
  });
  client.Start();
  ASSERT_TRUE(WaitFor([&] { return client.Status().up; }));
  agent.reset();
  // link_timeout 300 ms plus one poll turn.
  EXPECT_EQ(down.get_future().wait_for(std::chrono::milliseconds(1500)), std::future_status::ready);
  EXPECT_FALSE(client.Status().up);
}

TEST(AgentLinkClientTest, ReconnectsWhenTheAgentComesBack) {
  FakeAgent agent;
  AgentLinkClient client(OptionsFor(agent));
  client.Start();
  ASSERT_TRUE(client.Request(RequestState(), kWait).has_value());
  agent.server.Stop();
  EXPECT_FALSE(client.Request(RequestState(), std::chrono::milliseconds(200)).has_value());
  kapfix::agent::CommandServer again(agent.control, [&] {
    auto options = TestServerOptions();
    options.bind_endpoint = agent.command_endpoint;
    return options;
  }());
  again.Start();
  const auto reply = client.Request(RequestState(), kWait);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok()) << reply->reason();
}

TEST(AgentLinkClientTest, SequenceGapOnAStreamIsCounted) {
  // A raw PUB plays an agent that lost telemetry 2 and 3 on the way.
  zmq::context_t context(1);
  zmq::socket_t pub(context, zmq::socket_type::pub);
  pub.set(zmq::sockopt::linger, 0);
  pub.bind("tcp://127.0.0.1:*");
  const std::string endpoint = pub.get(zmq::sockopt::last_endpoint);
  UnusedPort commands;
  auto options = OptionsForPort(commands.port());
  options.stream_endpoint = endpoint;
  AgentLinkClient client(options);
  client.OnMessage("telemetry", [](const google::protobuf::Message&) {});
  client.Start();
  const auto send = [&](std::uint64_t sequence) {
    kapfix::v1::Telemetry telemetry;
    kapfix::v1::Stamp(telemetry.mutable_header(), kAgentId, sequence);
    (void)pub.send(zmq::buffer(std::string("telemetry")), zmq::send_flags::sndmore);
    (void)pub.send(zmq::buffer(telemetry.SerializeAsString()));
  };
  // Until the subscription arrives, PUB drops: send sequence 1 until it is seen.
  ASSERT_TRUE(WaitFor([&] {
    send(1);
    return client.Status().messages_received > 0;
  }));
  send(4);
  ASSERT_TRUE(WaitFor([&] { return client.Status().sequence_gaps > 0; }));
  EXPECT_EQ(client.Status().sequence_gaps, 2U);
  EXPECT_EQ(client.SequenceGaps("telemetry"), 2U);
  EXPECT_EQ(client.SequenceGaps("photo"), 0U);
}

TEST(AgentLinkClientTest, StopAnswersPendingRequestsWithNothing) {
  UnusedPort port;
  AgentLinkClient client(OptionsForPort(port.port()));
  client.Start();
  std::promise<bool> answered;
  client.RequestAsync(
      RequestState(), std::chrono::seconds(60),
      [&](std::optional<kapfix::v1::Reply> reply) { answered.set_value(reply.has_value()); });
  client.Stop();
  auto future = answered.get_future();
  ASSERT_EQ(future.wait_for(std::chrono::milliseconds(100)), std::future_status::ready);
  EXPECT_FALSE(future.get());
}

TEST(AgentLinkClientTest, RequestBeforeStartAnswersNothingAtOnce) {
  AgentLinkClient client(OptionsForPort(1));
  EXPECT_FALSE(client.Request(RequestState(), kWait).has_value());
}

}  // namespace
}  // namespace kapfix::testing
