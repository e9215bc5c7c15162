#pragma once

// Loopback helpers shared by the link tests: an in-process fake agent (CommandServer and
// StreamPublisher in front of FakeAgentControl, ephemeral ports on 127.0.0.1), a raw ZeroMQ
// station that sends exactly the frames a test wants, and a port on which nothing listens.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "agent/server/command_server.hpp"
#include "agent/server/stream_publisher.hpp"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/telemetry.pb.h"
#include "tests/link/fake_agent_control.hpp"
#include "tests/support/process.hpp"

namespace kapfix::testing {

inline constexpr const char* kAgentId = "test-agent";
// Every wait in these tests is bounded by this (a failing test fails, it does not hang).
inline constexpr auto kWait = std::chrono::milliseconds(3000);

// Polls `done` until it holds (true) or kWait has passed (false).
template <typename Predicate>
bool WaitFor(Predicate done) {
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// Telemetry of ~100 kB (padding in an unknown field keeps it valid): a few dozen fill the
// TCP buffers, so small high-water marks make the publisher drop.
kapfix::v1::Telemetry LargeTelemetry(std::uint64_t frame);

int PortOf(const std::string& endpoint);  // "tcp://127.0.0.1:41234" → 41234

// Fast heartbeats (50 ms) so that tests see the link come up quickly.
kapfix::agent::StreamPublisherOptions TestPublisherOptions();
kapfix::agent::CommandServerOptions TestServerOptions();

class FakeAgent {
 public:
  explicit FakeAgent(
      kapfix::agent::StreamPublisherOptions publisher_options = TestPublisherOptions(),
      kapfix::agent::CommandServerOptions server_options = TestServerOptions());

  FakeAgentControl control;
  kapfix::agent::StreamPublisher publisher;
  kapfix::agent::CommandServer server;
  std::string command_endpoint;
  std::string stream_endpoint;
};

// A command with a stamped header (protocol version, agent id, sequence).
kapfix::v1::Command Stamped(kapfix::v1::Command command, std::uint64_t sequence);

// One DEALER, as a station; sends frames verbatim.
class RawStation {
 public:
  explicit RawStation(const std::string& endpoint);

  void SendFrames(const std::vector<std::string>& frames);
  // ["", "command", bytes], the envelope AgentLinkClient uses.
  void SendCommandBytes(const std::string& bytes);
  std::optional<std::vector<std::string>> ReceiveFrames(std::chrono::milliseconds wait = kWait);
  // Sends `command` serialized and decodes the reply; std::nullopt when none came.
  std::optional<kapfix::v1::Reply> Exchange(const kapfix::v1::Command& command);
  std::optional<kapfix::v1::Reply> ExchangeBytes(const std::string& bytes);

 private:
  zmq::context_t context_{1};
  zmq::socket_t socket_;
};

// A SUB connected to `endpoint`, subscribed to `topics`; Ready() waits for the agent's
// heartbeat, which proves the subscription reached the publisher.
class RawSubscriber {
 public:
  RawSubscriber(const std::string& endpoint, const std::vector<std::string>& topics,
                int receive_high_water_mark = 1000);
  bool Ready();
  // [topic, payload] of the next message whose topic is `topic` (others skipped).
  std::optional<std::string> Next(const std::string& topic, std::chrono::milliseconds wait = kWait);

 private:
  zmq::context_t context_{1};
  zmq::socket_t socket_;
};

// A TCP port on 127.0.0.1 that is bound but not listening while this lives: connecting to
// it is refused, and nothing else can take it.
class UnusedPort {
 public:
  UnusedPort();
  ~UnusedPort();
  UnusedPort(const UnusedPort&) = delete;
  UnusedPort& operator=(const UnusedPort&) = delete;
  int port() const { return port_; }
  void Release();  // frees the port, e.g. for a server to bind it next

 private:
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace kapfix::testing
