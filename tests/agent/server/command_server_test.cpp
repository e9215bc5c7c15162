#include "agent/server/command_server.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <limits>
#include <string>

#include "kapfix/v1/heartbeat.pb.h"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using kapfix::v1::Command;
using ::testing::HasSubstr;

Command RequestState(std::uint64_t sequence) {
  Command command;
  command.mutable_request_state();
  return Stamped(command, sequence);
}

Command Fixate(std::uint64_t sequence) {
  Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_FIXATE);
  return Stamped(command, sequence);
}

// After any refusal the server must still answer a good command.
void ExpectStillServing(RawStation& station, std::uint64_t sequence) {
  const auto reply = station.Exchange(Fixate(sequence));
  ASSERT_TRUE(reply.has_value()) << "the server stopped answering";
  EXPECT_TRUE(reply->ok()) << reply->reason();
}

class CommandServerTest : public ::testing::Test {
 protected:
  FakeAgent agent;
  RawStation station{agent.command_endpoint};
};

TEST_F(CommandServerTest, AnswersACommandWithAStampedOkReply) {
  const auto reply = station.Exchange(Fixate(7));
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_UNSPECIFIED);
  EXPECT_EQ(reply->command_sequence(), 7U);
  EXPECT_EQ(reply->header().protocol_version(), kapfix::v1::kProtocolVersion);
  EXPECT_EQ(reply->header().agent_id(), kAgentId);
  EXPECT_EQ(reply->header().sequence(), 1U);
  EXPECT_GT(reply->header().send_time_us(), 0);
  ASSERT_EQ(agent.control.commands().size(), 1U);
  EXPECT_EQ(agent.control.State().mode(), kapfix::v1::MODE_FIXATE);
}

TEST_F(CommandServerTest, RequestStateReplyCarriesTheAgentState) {
  const auto reply = station.Exchange(RequestState(1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->state().frame_width_px(), 640U);
  EXPECT_EQ(reply->state().search().strategy(), "h23");
}

TEST_F(CommandServerTest, MalformedBytesGetAMalformedReplyAndTheServerKeepsServing) {
  const auto reply = station.ExchangeBytes("\xff\xff\xff\xff not a protobuf");
  ASSERT_TRUE(reply.has_value());
  EXPECT_FALSE(reply->ok());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_THAT(reply->reason(), HasSubstr("malformed"));
  EXPECT_EQ(reply->command_sequence(), 0U);
  ExpectStillServing(station, 1);
  EXPECT_EQ(agent.control.commands().size(), 1U);
}

TEST_F(CommandServerTest, OversizedCommandGetsAnOversizedReplyAndTheServerKeepsServing) {
  Command command;
  command.mutable_take_photo()->set_note(std::string(kapfix::v1::kMaxCommandBytes, 'x'));
  const auto reply = station.Exchange(Stamped(command, 1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_OVERSIZED);
  EXPECT_THAT(reply->reason(), HasSubstr("exceed the limit of 65536 bytes"));
  ExpectStillServing(station, 2);
  EXPECT_EQ(agent.control.commands().size(), 1U);
}

TEST_F(CommandServerTest, FrameBeyondTheTransportLimitOnlyCostsItsSenderTheConnection) {
  // libzmq drops such a peer without delivering anything (ZMQ_MAXMSGSIZE): no reply is
  // possible, but the server and other stations go on.
  station.SendCommandBytes(std::string(4 * kapfix::v1::kMaxCommandBytes + 1, 'x'));
  EXPECT_FALSE(station.ReceiveFrames(std::chrono::milliseconds(300)).has_value());
  RawStation other(agent.command_endpoint);
  ExpectStillServing(other, 1);
  EXPECT_EQ(agent.control.commands().size(), 1U);
}

TEST_F(CommandServerTest, WrongProtocolVersionIsRefusedNamingBothVersions) {
  Command command = Fixate(4);
  command.mutable_header()->set_protocol_version(2);
  const auto reply = station.Exchange(command);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_WRONG_VERSION);
  EXPECT_THAT(reply->reason(), HasSubstr("got 2, this side speaks 1"));
  EXPECT_EQ(reply->command_sequence(), 4U);  // so the station can match it to its request
  ExpectStillServing(station, 5);
}

TEST_F(CommandServerTest, CommandWithoutHeaderIsRefused) {
  Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_FIXATE);
  const auto reply = station.Exchange(command);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_MISSING_HEADER);
  EXPECT_TRUE(agent.control.commands().empty());
}

TEST_F(CommandServerTest, ReplayedSequenceIsRefusedAndNotExecuted) {
  ASSERT_TRUE(station.Exchange(Fixate(5))->ok());
  const auto reply = station.Exchange(Fixate(5));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_STALE_SEQUENCE);
  EXPECT_THAT(reply->reason(), HasSubstr("replayed sequence number 5"));
  EXPECT_EQ(agent.control.commands().size(), 1U);
  ExpectStillServing(station, 6);
}

TEST_F(CommandServerTest, LowerSequenceIsRefusedAsStale) {
  ASSERT_TRUE(station.Exchange(Fixate(9))->ok());
  const auto reply = station.Exchange(Fixate(8));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_STALE_SEQUENCE);
  EXPECT_THAT(reply->reason(), HasSubstr("stale sequence number 8"));
}

TEST_F(CommandServerTest, SequencesAreCheckedPerConnection) {
  ASSERT_TRUE(station.Exchange(Fixate(5))->ok());
  RawStation other(agent.command_endpoint);
  const auto reply = other.Exchange(Fixate(1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_TRUE(reply->ok()) << reply->reason();
}

TEST_F(CommandServerTest, NaNGainIsRefusedBeforeReachingTheAgent) {
  Command command;
  command.mutable_set_gains()->set_p(std::numeric_limits<float>::quiet_NaN());
  const auto reply = station.Exchange(Stamped(command, 1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
  EXPECT_THAT(reply->reason(), HasSubstr("set_gains.p = nan"));
  EXPECT_TRUE(agent.control.commands().empty());
  ExpectStillServing(station, 2);
}

TEST_F(CommandServerTest, CommandWithNoCommandFieldIsUnknown) {
  const auto reply = station.Exchange(Stamped(Command(), 1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND);
  EXPECT_TRUE(agent.control.commands().empty());
}

TEST_F(CommandServerTest, CommandAddressedToAnotherAgentIsRefused) {
  Command command = Fixate(1);
  command.mutable_header()->set_agent_id("boat-2");
  const auto reply = station.Exchange(command);
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_UNAUTHORIZED);
  EXPECT_THAT(reply->reason(), HasSubstr("'boat-2'"));
  EXPECT_TRUE(agent.control.commands().empty());
}

TEST_F(CommandServerTest, AgentRefusalReachesTheStationWithItsReason) {
  agent.control.RefuseWith(kapfix::v1::ERROR_CODE_WRONG_MODE, "calibrate first");
  const auto reply = station.Exchange(Fixate(1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_FALSE(reply->ok());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_WRONG_MODE);
  EXPECT_EQ(reply->reason(), "calibrate first");
}

TEST_F(CommandServerTest, ExceptionInTheAgentBecomesAnInternalErrorAndTheServerKeepsServing) {
  agent.control.ThrowOnExecute("servo bus exploded");
  const auto reply = station.Exchange(Fixate(1));
  ASSERT_TRUE(reply.has_value());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_INTERNAL);
  EXPECT_THAT(reply->reason(), HasSubstr("servo bus exploded"));
  const auto again = station.Exchange(RequestState(2));
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->command_sequence(), 2U);
}

TEST_F(CommandServerTest, TooManyFramesAreMalformed) {
  station.SendFrames({"", "command", Fixate(1).SerializeAsString(), "extra", "more"});
  const auto frames = station.ReceiveFrames();
  ASSERT_TRUE(frames.has_value());
  kapfix::v1::Reply reply;
  ASSERT_TRUE(reply.ParseFromString(frames->back()));
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_THAT(reply.reason(), HasSubstr("got 4 frames"));
  EXPECT_TRUE(agent.control.commands().empty());
}

TEST_F(CommandServerTest, CommandUnderAnotherTopicIsMalformed) {
  station.SendFrames({"", "telemetry", Fixate(1).SerializeAsString()});
  const auto frames = station.ReceiveFrames();
  ASSERT_TRUE(frames.has_value());
  kapfix::v1::Reply reply;
  ASSERT_TRUE(reply.ParseFromString(frames->back()));
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_THAT(reply.reason(), HasSubstr("topic 'telemetry'"));
}

TEST_F(CommandServerTest, ReqSocketWithoutTopicFrameIsAnswered) {
  zmq::context_t context(1);
  zmq::socket_t req(context, zmq::socket_type::req);
  req.set(zmq::sockopt::linger, 0);
  req.set(zmq::sockopt::rcvtimeo, static_cast<int>(kWait.count()));
  req.connect(agent.command_endpoint);
  (void)req.send(zmq::buffer(Fixate(1).SerializeAsString()));
  zmq::message_t answer;
  ASSERT_TRUE(req.recv(answer).has_value());
  kapfix::v1::Reply reply;
  ASSERT_TRUE(reply.ParseFromString(answer.to_string()));
  EXPECT_TRUE(reply.ok()) << reply.reason();
}

TEST_F(CommandServerTest, StationHeartbeatIsEchoed) {
  kapfix::v1::Heartbeat heartbeat;
  kapfix::v1::Stamp(heartbeat.mutable_header(), kAgentId, 3);
  station.SendFrames({"", "heartbeat", heartbeat.SerializeAsString()});
  const auto frames = station.ReceiveFrames();
  ASSERT_TRUE(frames.has_value());
  ASSERT_EQ(frames->size(), 3U);
  EXPECT_EQ((*frames)[1], "heartbeat");
  kapfix::v1::Heartbeat echo;
  ASSERT_TRUE(echo.ParseFromString((*frames)[2]));
  EXPECT_EQ(echo.echoed_send_time_us(), heartbeat.header().send_time_us());
  EXPECT_EQ(echo.echoed_sequence(), 3U);
  EXPECT_GE(echo.echo_hold_us(), 0);
  EXPECT_EQ(agent.server.counters().heartbeats_echoed, 1U);
}

TEST_F(CommandServerTest, CountsOkAndRefusedReplies) {
  ASSERT_TRUE(station.Exchange(Fixate(1)).has_value());
  ASSERT_TRUE(station.ExchangeBytes("junk").has_value());
  const auto counters = agent.server.counters();
  EXPECT_EQ(counters.commands_ok, 1U);
  EXPECT_EQ(counters.commands_refused, 1U);
  EXPECT_GT(counters.last_station_heard_us, 0);
}

TEST(CommandServerLifecycleTest, BindingAnAddressInUseThrows) {
  FakeAgent agent;
  FakeAgentControl control;
  auto options = TestServerOptions();
  options.bind_endpoint = agent.command_endpoint;
  kapfix::agent::CommandServer second(control, options);
  EXPECT_THROW(second.Start(), std::runtime_error);
}

TEST(CommandServerLifecycleTest, StopReturnsPromptly) {
  FakeAgent agent;
  const auto start = std::chrono::steady_clock::now();
  agent.server.Stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(500));
}

}  // namespace
}  // namespace kapfix::testing
