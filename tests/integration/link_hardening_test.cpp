// Issue 15: what a hostile or broken peer could still do to the real agent, each on loopback
// against kapfix-agent --sim, each failing before the hardening.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>
#include <zmq.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "kapfix/v1/envelope_codec.hpp"
#include "tests/integration/agent_process.hpp"
#include "tests/link/link_test_support.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;

// [kB] the resident set of a process, from /proc.
long ResidentKb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kb = 0;
      status >> kb;
      return kb;
    }
  }
  return -1;
}

// A request_state command addressed to any agent, stamped now.
kapfix::v1::Command StateRequest(std::uint64_t sequence) {
  kapfix::v1::Command command;
  command.mutable_request_state();
  kapfix::v1::Stamp(command.mutable_header(), "", sequence);
  return command;
}

// The agent answers: retried while it starts (each try a new sequence number and send time).
std::optional<kapfix::v1::Reply> FirstReply(RawStation& station, std::uint64_t* sequence) {
  for (int attempt = 0; attempt < 10; ++attempt) {
    if (auto reply = station.Exchange(StateRequest(++*sequence))) return reply;
  }
  return std::nullopt;
}

// Sets the soft limit on open files of this process; returns the previous one.
rlim_t SetOpenFileLimit(rlim_t soft) {
  rlimit limit{};
  getrlimit(RLIMIT_NOFILE, &limit);
  const rlim_t previous = limit.rlim_cur;
  limit.rlim_cur = std::min(soft, limit.rlim_max);
  setrlimit(RLIMIT_NOFILE, &limit);
  return previous;
}

// Item 1: one 64 MiB subscription took the agent to 6.8 GB. It is now refused by the
// publisher's maximum message size before anything is allocated for it, and the peer dropped.
TEST(LinkHardeningTest, SubscriptionOf64MiBLeavesTheAgentsMemoryWithin16MB) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  const long before_kb = ResidentKb(agent.pid());

  zmq::context_t context(1);
  zmq::socket_t xsub(context, zmq::socket_type::xsub);
  xsub.set(zmq::sockopt::linger, 0);
  xsub.set(zmq::sockopt::reconnect_ivl, -1);  // one attempt: the agent's answer is to hang up
  ASSERT_EQ(zmq_socket_monitor(xsub.handle(), "inproc://monitor", ZMQ_EVENT_DISCONNECTED), 0);
  zmq::socket_t monitor(context, zmq::socket_type::pair);
  monitor.set(zmq::sockopt::rcvtimeo, 30'000);
  monitor.connect("inproc://monitor");
  xsub.connect(agent.stream_endpoint());
  std::string subscription(std::size_t{64} << 20U, 'a');
  subscription[0] = 1;  // XSUB: 1 = subscribe, then the prefix
  ASSERT_TRUE(xsub.send(zmq::buffer(subscription), zmq::send_flags::none));
  zmq::message_t event;
  ASSERT_TRUE(monitor.recv(event)) << "the agent kept the connection of a 64 MiB subscription";

  // The agent still answers, and its memory did not grow with the subscription.
  ASSERT_TRUE(station.Exchange(StateRequest(++sequence))) << agent.log();
  const long after_kb = ResidentKb(agent.pid());
  std::printf("agent RSS %ld kB before, %ld kB after a 64 MiB subscription\n", before_kb, after_kb);
  EXPECT_LT(after_kb - before_kb, 16 * 1024);
}

// Item 2: libzmq reads 'A;B' as "bind B from source A": the agent listened on 0.0.0.0.
TEST(LinkHardeningTest, SourceAndBindPairCommandAddressIsRefused) {
  TempDir temp;
  UnusedPort open_port;
  UnusedPort stream;
  const ProcessOutcome run = RunProcess(
      std::string(KAPFIX_AGENT) + " --sim --frames 1 --command-address " +
          "'tcp://127.0.0.1:0;0.0.0.0:" + std::to_string(open_port.port()) + "'" +
          " --stream-address tcp://127.0.0.1:" + std::to_string(stream.port()) + " --photos " +
          (temp.path() / "photos").string() + " --state-dir " + (temp.path() / "state").string(),
      temp.path() / "agent.err");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.err, HasSubstr("';' is not allowed"));
}

TEST(LinkHardeningTest, SourceAndBindPairInTheConfigurationIsRefused) {
  TempDir temp;
  UnusedPort open_port;
  UnusedPort stream;
  std::ofstream(temp.path() / "agent.json")
      << R"({"link": {"command": "tcp://127.0.0.1:0;0.0.0.0:)" << open_port.port() << R"("}})";
  const ProcessOutcome run = RunProcess(
      std::string(KAPFIX_AGENT) + " --sim --frames 1 --config " +
          (temp.path() / "agent.json").string() + " --stream-address " +
          "tcp://127.0.0.1:" + std::to_string(stream.port()) + " --photos " +
          (temp.path() / "photos").string() + " --state-dir " + (temp.path() / "state").string(),
      temp.path() / "agent.err");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.err, HasSubstr("';'"));
}

// Item 2: "tcp://localhost:P" passed the loopback check but libzmq could not bind it.
TEST(LinkHardeningTest, LocalhostCommandAddressIsBoundOnLoopback) {
  UnusedPort port;
  const int number = port.port();
  port.Release();
  AgentProcess agent(
      {"--mode", "idle", "--command-address", "tcp://localhost:" + std::to_string(number)});
  RawStation station("tcp://127.0.0.1:" + std::to_string(number));
  std::uint64_t sequence = 0;
  EXPECT_TRUE(FirstReply(station, &sequence)) << agent.log();
}

// Item 3: the agent ran out of file descriptors (soft limit 1,024, a silent connection held
// 30 s) and refused every station. It raises its limit and closes silent connections.
TEST(LinkHardeningTest, AuthorisedStationIsAnsweredBehind1100SilentConnections) {
  const rlim_t previous = SetOpenFileLimit(1024);  // what the agent inherits, as under systemd
  AgentProcess agent({"--mode", "idle"});
  SetOpenFileLimit(previous);
  {
    RawStation first(agent.command_endpoint());
    std::uint64_t sequence = 0;
    ASSERT_TRUE(FirstReply(first, &sequence)) << agent.log();
  }
  constexpr int kSilent = 1100;
  std::vector<int> silent;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(agent.command_port()));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (int i = 0; i < kSilent; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
    ASSERT_GE(fd, 0) << "the test's own descriptors ran out at " << i;
    (void)::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address);
    silent.push_back(fd);
  }
  RawStation station(agent.command_endpoint());
  const auto asked = std::chrono::steady_clock::now();
  const auto reply = station.Exchange(StateRequest(1));
  const double waited_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - asked).count();
  for (const int fd : silent) ::close(fd);
  ASSERT_TRUE(reply.has_value()) << agent.log();
  EXPECT_TRUE(reply->ok()) << reply->reason();
  std::printf("reply behind %d silent connections after %.0f ms (target: under 1 s)\n", kSilent,
              waited_ms);
}

// Item 8: captured command bytes were accepted again on a new connection.
TEST(LinkHardeningTest, ReplayedCommandOnANewConnectionIsRefused) {
  AgentProcess agent({"--mode", "idle"});
  std::uint64_t sequence = 0;
  std::string captured;
  {
    RawStation station(agent.command_endpoint());
    ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
    captured = StateRequest(++sequence).SerializeAsString();
    const auto first = station.ExchangeBytes(captured);
    ASSERT_TRUE(first && first->ok()) << (first ? first->reason() : "no reply");
  }
  RawStation attacker(agent.command_endpoint());
  const auto replayed = attacker.ExchangeBytes(captured);
  ASSERT_TRUE(replayed.has_value());
  EXPECT_FALSE(replayed->ok());
  EXPECT_EQ(replayed->error(), kapfix::v1::ERROR_CODE_STALE_SEQUENCE);
  EXPECT_THAT(replayed->reason(), HasSubstr("replayed"));
}

TEST(LinkHardeningTest, CommandStamped1970IsRefusedNamingTheSkew) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  kapfix::v1::Command old = StateRequest(++sequence);
  old.mutable_header()->set_send_time_us(1);
  const auto reply = station.Exchange(old);
  ASSERT_TRUE(reply.has_value());
  EXPECT_FALSE(reply->ok());
  EXPECT_THAT(reply->reason(), HasSubstr("behind the agent's clock"));
}

}  // namespace
}  // namespace kapfix::testing
