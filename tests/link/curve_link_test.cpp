// CurveZMQ on the link (issue 5): only a station whose public key the agent lists may command
// it or read its streams; everyone else is stopped in the handshake.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "link/agent_link_client.hpp"
#include "link/curve_key_pair.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::link::AgentLinkClient;
using kapfix::link::AgentLinkClientOptions;
using kapfix::link::CurveClientKeys;
using kapfix::link::CurveKeyPair;
using kapfix::link::CurveServerKeys;
using kapfix::link::GenerateCurveKeyPair;
using kapfix::v1::Command;
using ::testing::HasSubstr;

// How long a refused station is given to get through anyway.
constexpr auto kRefusedWait = std::chrono::milliseconds(1500);

Command RequestState() {
  Command command;
  command.mutable_request_state();
  return command;
}

// A TCP connection that never says a word of ZMTP, held open for the life of the object.
class SilentTcpConnection {
 public:
  explicit SilentTcpConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~SilentTcpConnection() { ::close(fd_); }
  SilentTcpConnection(const SilentTcpConnection&) = delete;
  SilentTcpConnection& operator=(const SilentTcpConnection&) = delete;
  bool connected() const { return connected_; }

 private:
  int fd_;
  bool connected_ = false;
};

// The agent's log lines (spdlog's default logger) while this lives.
class CapturedLog {
 public:
  CapturedLog() : previous_(spdlog::default_logger()) {
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(lines_, /*force_flush=*/true);
    spdlog::set_default_logger(std::make_shared<spdlog::logger>("captured", sink));
  }
  ~CapturedLog() { spdlog::set_default_logger(previous_); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;

  // [count] lines so far containing `first` and, after it, `second`.
  int Count(const std::string& first, const std::string& second) {
    spdlog::default_logger()->flush();
    std::istringstream all(lines_.str());
    int count = 0;
    for (std::string line; std::getline(all, line);) {
      const std::size_t at = line.find(first);
      count += at != std::string::npos && line.find(second, at) != std::string::npos;
    }
    return count;
  }

 private:
  std::shared_ptr<spdlog::logger> previous_;
  std::ostringstream lines_;
};

// A ZMTP 3.0 greeting offering the NULL mechanism to a CurveZMQ server: a garbage handshake.
void SendPlainGreeting(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0) {
    std::string greeting(64, '\0');
    greeting[0] = static_cast<char>(0xFF);
    greeting[9] = 0x7F;
    greeting[10] = 3;
    greeting.replace(12, 4, "NULL");
    (void)::send(fd, greeting.data(), greeting.size(), MSG_NOSIGNAL);
    char byte = 0;
    while (::recv(fd, &byte, 1, 0) > 0) {  // until the agent hangs up
    }
  }
  ::close(fd);
}

// Waits until `done()` or 30 s pass (a hang guard only); whether it became true.
template <typename Condition>
bool WaitUntil(Condition done) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!done()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

class CurveLinkTest : public ::testing::Test {
 protected:
  CurveLinkTest() : agent_(PublisherOptions(), ServerOptions()) {}

  CurveServerKeys AgentKeys() const {
    return {agent_keys_.secret_key, {{authorised_.public_key, "laptop"}}};
  }
  kapfix::agent::StreamPublisherOptions PublisherOptions() const {
    auto options = TestPublisherOptions();
    options.curve = AgentKeys();
    return options;
  }
  kapfix::agent::CommandServerOptions ServerOptions() const {
    auto options = TestServerOptions();
    options.curve = AgentKeys();
    return options;
  }
  AgentLinkClientOptions ClientOptions(std::optional<CurveClientKeys> curve) const {
    AgentLinkClientOptions options;
    options.command_endpoint = agent_.command_endpoint;
    options.stream_endpoint = agent_.stream_endpoint;
    options.heartbeat_interval = std::chrono::milliseconds(50);
    options.link_timeout = std::chrono::milliseconds(300);
    options.curve = std::move(curve);
    return options;
  }
  CurveClientKeys StationKeys(const CurveKeyPair& station) const {
    return {station, agent_keys_.public_key};
  }

  const CurveKeyPair agent_keys_ = GenerateCurveKeyPair();
  const CurveKeyPair authorised_ = GenerateCurveKeyPair();
  FakeAgent agent_;
};

TEST_F(CurveLinkTest, AuthorisedStationCommandsTheAgent) {
  AgentLinkClient client(ClientOptions(StationKeys(authorised_)));
  client.Start();
  const auto reply = client.Request(RequestState(), kWait);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok()) << reply->reason();
  EXPECT_EQ(agent_.control.commands().size(), 1U);
}

TEST_F(CurveLinkTest, AuthorisedStationReadsTheStreams) {
  AgentLinkClient client(ClientOptions(StationKeys(authorised_)));
  client.Start();
  EXPECT_TRUE(client.WaitForStreams(kWait));
}

TEST_F(CurveLinkTest, UnknownKeyCannotCommandTheAgent) {
  AgentLinkClient client(ClientOptions(StationKeys(GenerateCurveKeyPair())));
  client.Start();
  EXPECT_FALSE(client.Request(RequestState(), kRefusedWait).has_value());
  EXPECT_TRUE(agent_.control.commands().empty());
  EXPECT_GT(agent_.server.counters().keys_refused, 0U);
}

TEST_F(CurveLinkTest, UnknownKeyCannotReadTheStreams) {
  AgentLinkClient client(ClientOptions(StationKeys(GenerateCurveKeyPair())));
  client.Start();
  EXPECT_FALSE(client.WaitForStreams(kRefusedWait));
  EXPECT_EQ(client.Status().messages_received, 0U);
}

TEST_F(CurveLinkTest, UnknownKeyIsToldWhyItWasRefused) {
  AgentLinkClient client(ClientOptions(StationKeys(GenerateCurveKeyPair())));
  client.Start();
  (void)client.Request(RequestState(), kRefusedWait);
  EXPECT_THAT(client.Status().handshake_failure, HasSubstr("refused this station's key"));
}

// A "key" whose halves do not belong together: the authorised public key claimed with
// another secret, i.e. a station posing as an authorised one.
TEST_F(CurveLinkTest, GarbageKeyClaimingAnAuthorisedPublicKeyCannotCommandTheAgent) {
  CurveKeyPair impostor = GenerateCurveKeyPair();
  impostor.public_key = authorised_.public_key;
  AgentLinkClient client(ClientOptions(StationKeys(impostor)));
  client.Start();
  EXPECT_FALSE(client.Request(RequestState(), kRefusedWait).has_value());
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CurveLinkTest, GarbageKeyClaimingAnAuthorisedPublicKeyCannotReadTheStreams) {
  CurveKeyPair impostor = GenerateCurveKeyPair();
  impostor.public_key = authorised_.public_key;
  AgentLinkClient client(ClientOptions(StationKeys(impostor)));
  client.Start();
  EXPECT_FALSE(client.WaitForStreams(kRefusedWait));
}

TEST_F(CurveLinkTest, PlainClientCannotCommandTheAgent) {
  RawStation plain(agent_.command_endpoint);
  EXPECT_FALSE(plain.Exchange(Stamped(RequestState(), 1)).has_value());
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CurveLinkTest, PlainClientCannotReadTheStreams) {
  AgentLinkClient client(ClientOptions(std::nullopt));
  client.Start();
  EXPECT_FALSE(client.WaitForStreams(kRefusedWait));
  EXPECT_EQ(client.Status().messages_received, 0U);
}

TEST_F(CurveLinkTest, SilentTcpConnectionsDoNotBlockAnAuthorisedStation) {
  std::vector<std::unique_ptr<SilentTcpConnection>> squatters;
  for (const std::string& endpoint : {agent_.command_endpoint, agent_.stream_endpoint}) {
    for (int i = 0; i < 4; ++i) {
      squatters.push_back(std::make_unique<SilentTcpConnection>(PortOf(endpoint)));
      ASSERT_TRUE(squatters.back()->connected());
    }
  }
  AgentLinkClient client(ClientOptions(StationKeys(authorised_)));
  client.Start();
  const auto reply = client.Request(RequestState(), kWait);
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok());
  EXPECT_TRUE(client.WaitForStreams(kWait));
}

// Issue 15, item 11: a fresh key per connection got one log line each (2,000 in 5.4 s, all
// forwarded to the stations); forged-key and garbage handshakes got none. Now every refusal is
// counted and the log gets at most one line per 10 s of each kind in all, whatever the number
// of keys or connections.
TEST_F(CurveLinkTest, RefusedHandshakesAreLoggedInSummaryWhateverTheKeyOrNumber) {
  CapturedLog log;
  const auto start = std::chrono::steady_clock::now();
  constexpr int kEach = 20;
  std::vector<std::unique_ptr<AgentLinkClient>> refused;
  for (int i = 0; i < kEach; ++i) {  // a fresh key each, as an attacker would
    refused.push_back(
        std::make_unique<AgentLinkClient>(ClientOptions(StationKeys(GenerateCurveKeyPair()))));
    refused.back()->Start();
  }
  CurveKeyPair forged = GenerateCurveKeyPair();
  forged.public_key = authorised_.public_key;
  AgentLinkClient impostor(ClientOptions(StationKeys(forged)));
  impostor.Start();
  for (int i = 0; i < kEach; ++i) SendPlainGreeting(PortOf(agent_.command_endpoint));
  ASSERT_TRUE(WaitUntil([&] { return agent_.server.counters().keys_refused >= kEach; }));
  ASSERT_TRUE(WaitUntil([&] {
    return agent_.server.counters().handshakes_failed >= std::uint64_t{2} * kEach;
  })) << agent_.server.counters().handshakes_failed
      << " failed handshakes counted";
  refused.clear();
  const auto elapsed = std::chrono::steady_clock::now() - start;

  // One line per 10 s period at most (and a first line at once), of each kind.
  const int allowed = 1 + static_cast<int>(elapsed / std::chrono::seconds(10));
  const auto counters = agent_.server.counters();
  const int key_lines = log.Count("command server: ", "refused a connection from");
  const int summary_lines = log.Count("command server: ", "handshake(s) refused");
  std::printf("%llu key refusals and %llu failed handshakes in %.1f s: %d + %d log lines\n",
              static_cast<unsigned long long>(counters.keys_refused),
              static_cast<unsigned long long>(counters.handshakes_failed),
              std::chrono::duration<double>(elapsed).count(), key_lines, summary_lines);
  EXPECT_GE(key_lines, 1);
  EXPECT_LE(key_lines, allowed);
  EXPECT_GE(summary_lines, 1);
  EXPECT_LE(summary_lines, allowed);
}

}  // namespace
}  // namespace kapfix::testing
