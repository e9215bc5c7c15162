// CurveZMQ on the link (issue 5): only a station whose public key the agent lists may command
// it or read its streams; everyone else is stopped in the handshake.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <vector>

#include "kapfix/link/curve_key_pair.hpp"
#include "tests/link/link_test_support.hpp"
#include "tools/ctl/agent_link_client.hpp"

namespace kapfix::testing {
namespace {

using kapfix::agent::CurveServerKeys;
using kapfix::link::AgentLinkClient;
using kapfix::link::AgentLinkClientOptions;
using kapfix::link::CurveClientKeys;
using kapfix::link::CurveKeyPair;
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

}  // namespace
}  // namespace kapfix::testing
