// The command server's rate limit over loopback (issue 15): a station that sends faster than
// its rate is refused with ERROR_CODE_RATE_LIMITED naming the rate, before its command is
// validated or executed; another station is answered meanwhile; a reconnection does not give
// a station a fresh bucket. Rates of 0.1 command/s: no token comes back within a test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "link/curve_key_pair.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::agent::CommandRateLimitOptions;
using kapfix::agent::CommandServerOptions;
using kapfix::link::CurveKeyPair;
using kapfix::link::GenerateCurveKeyPair;
using kapfix::v1::Command;
using kapfix::v1::Reply;
using ::testing::HasSubstr;

constexpr int kBurst = 3;  // [commands] per station

CommandRateLimitOptions SlowRates(double all_burst) {
  CommandRateLimitOptions options;
  options.station_per_s = 0.1;
  options.station_burst = kBurst;
  options.all_per_s = 0.1;
  options.all_burst = all_burst;
  return options;
}

Command RequestState() {
  Command command;
  command.mutable_request_state();
  return command;
}

// A DEALER with a CurveZMQ key pair, as a station: ["", "command", bytes] out, the reply in.
class CurveStation {
 public:
  CurveStation(const std::string& endpoint, const CurveKeyPair& own,
               const std::string& agent_public_key)
      : socket_(context_, zmq::socket_type::dealer) {
    socket_.set(zmq::sockopt::linger, 0);
    socket_.set(zmq::sockopt::rcvtimeo, static_cast<int>(kWait.count()));
    socket_.set(zmq::sockopt::curve_serverkey, agent_public_key);
    socket_.set(zmq::sockopt::curve_publickey, own.public_key);
    socket_.set(zmq::sockopt::curve_secretkey, own.secret_key);
    socket_.connect(endpoint);
  }

  std::optional<Reply> Exchange(const Command& command) {
    const std::string bytes = Stamped(command, ++sequence_).SerializeAsString();
    (void)socket_.send(zmq::message_t(), zmq::send_flags::sndmore);
    (void)socket_.send(zmq::buffer(std::string_view("command")), zmq::send_flags::sndmore);
    (void)socket_.send(zmq::buffer(bytes), zmq::send_flags::none);
    std::vector<zmq::message_t> frames;
    bool more = true;
    while (more) {
      zmq::message_t frame;
      if (!socket_.recv(frame)) return std::nullopt;
      more = frame.more();
      frames.push_back(std::move(frame));
    }
    Reply reply;
    if (!reply.ParseFromArray(frames.back().data(), static_cast<int>(frames.back().size()))) {
      return std::nullopt;
    }
    return reply;
  }
  std::uint64_t sequence() const { return sequence_; }

 private:
  zmq::context_t context_{1};
  zmq::socket_t socket_;
  std::uint64_t sequence_ = 0;
};

class CommandServerRateLimitTest : public ::testing::Test {
 protected:
  std::unique_ptr<FakeAgent> StartAgent(double all_burst) {
    CommandServerOptions options = TestServerOptions();
    options.curve = kapfix::link::CurveServerKeys{
        agent_keys_.secret_key, {{first_.public_key, "first"}, {second_.public_key, "second"}}};
    options.rate_limit = SlowRates(all_burst);
    return std::make_unique<FakeAgent>(TestPublisherOptions(), options);
  }
  std::unique_ptr<CurveStation> Connect(const FakeAgent& agent, const CurveKeyPair& keys) const {
    return std::make_unique<CurveStation>(agent.command_endpoint, keys, agent_keys_.public_key);
  }

  const CurveKeyPair agent_keys_ = GenerateCurveKeyPair();
  const CurveKeyPair first_ = GenerateCurveKeyPair();
  const CurveKeyPair second_ = GenerateCurveKeyPair();
};

// Sends request_state until the burst is used; whether each got an OK reply.
bool UseTheBurst(CurveStation& station) {
  for (int i = 0; i < kBurst; ++i) {
    const std::optional<Reply> reply = station.Exchange(RequestState());
    if (!reply || !reply->ok()) return false;
  }
  return true;
}

TEST_F(CommandServerRateLimitTest, StationOverItsRateIsRefusedNamingTheRate) {
  const auto agent = StartAgent(100);
  const auto station = Connect(*agent, first_);
  ASSERT_TRUE(UseTheBurst(*station));
  const std::size_t executed = agent->control.commands().size();
  const std::optional<Reply> refused = station->Exchange(RequestState());
  ASSERT_TRUE(refused.has_value());
  EXPECT_FALSE(refused->ok());
  EXPECT_EQ(refused->error(), kapfix::v1::ERROR_CODE_RATE_LIMITED);
  EXPECT_THAT(refused->reason(), HasSubstr("at most 0.1 commands/s per station"));
  EXPECT_EQ(refused->command_sequence(), station->sequence());  // the station can match it
  EXPECT_EQ(agent->control.commands().size(), executed);        // never reached the agent
  EXPECT_EQ(agent->server.counters().commands_rate_limited, 1U);
}

TEST_F(CommandServerRateLimitTest, HeldStationIsAnsweredAgainWhenItsHoldEnds) {
  const auto agent = StartAgent(100);
  const auto station = Connect(*agent, first_);
  ASSERT_TRUE(UseTheBurst(*station));
  // The first refusal holds the connection (at most a second); the next command is read, and
  // refused, after that.
  for (int i = 0; i < 2; ++i) {
    const std::optional<Reply> reply = station->Exchange(RequestState());
    ASSERT_TRUE(reply.has_value()) << "refusal " << i;
    EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_RATE_LIMITED);
  }
}

TEST_F(CommandServerRateLimitTest, AnotherStationIsAnsweredWhileOneIsOverItsRate) {
  const auto agent = StartAgent(100);
  const auto flooding = Connect(*agent, first_);
  const auto quiet = Connect(*agent, second_);
  ASSERT_TRUE(UseTheBurst(*flooding));
  ASSERT_EQ(flooding->Exchange(RequestState())->error(), kapfix::v1::ERROR_CODE_RATE_LIMITED);
  const std::optional<Reply> answered = quiet->Exchange(RequestState());
  ASSERT_TRUE(answered.has_value());
  EXPECT_TRUE(answered->ok()) << answered->reason();
  EXPECT_TRUE(answered->has_state());
}

TEST_F(CommandServerRateLimitTest, ReconnectingDoesNotRefillTheStationsBucket) {
  const auto agent = StartAgent(100);
  ASSERT_TRUE(UseTheBurst(*Connect(*agent, first_)));
  const std::optional<Reply> again = Connect(*agent, first_)->Exchange(RequestState());
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->error(), kapfix::v1::ERROR_CODE_RATE_LIMITED) << again->reason();
}

TEST_F(CommandServerRateLimitTest, AllStationsTogetherAreHeldToTheSharedRate) {
  const auto agent = StartAgent(kBurst + 1);
  ASSERT_TRUE(UseTheBurst(*Connect(*agent, first_)));
  const auto second = Connect(*agent, second_);
  ASSERT_TRUE(second->Exchange(RequestState())->ok());  // the shared bucket's last token
  const std::optional<Reply> refused = second->Exchange(RequestState());
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->error(), kapfix::v1::ERROR_CODE_RATE_LIMITED);
  EXPECT_THAT(refused->reason(), HasSubstr("at most 0.1 commands/s from all stations together"));
}

TEST(CommandServerPlainRateLimitTest, PlainStationsFromOneAddressShareABucket) {
  CommandServerOptions options = TestServerOptions();
  options.rate_limit = SlowRates(100);
  FakeAgent agent(TestPublisherOptions(), options);
  RawStation first(agent.command_endpoint);
  for (std::uint64_t sequence = 1; sequence <= kBurst; ++sequence) {
    ASSERT_TRUE(first.Exchange(Stamped(RequestState(), sequence))->ok());
  }
  RawStation second(agent.command_endpoint);  // a new connection from 127.0.0.1
  const std::optional<Reply> refused = second.Exchange(Stamped(RequestState(), 1));
  ASSERT_TRUE(refused.has_value());
  EXPECT_EQ(refused->error(), kapfix::v1::ERROR_CODE_RATE_LIMITED);
}

}  // namespace
}  // namespace kapfix::testing
