// The live client against the real link on loopback: tests/link's FakeAgent is the agent's
// own CommandServer and StreamPublisher in front of a fake pipeline.
#include "groundstation/client/zmq_agent_client.hpp"

#include <gtest/gtest.h>

#include <QElapsedTimer>
#include <QSignalSpy>
#include <QTimer>
#include <memory>

#include "tests/groundstation/station_test_support.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::station {
namespace {

using kapfix::testing::FakeAgent;
using testing::WaitUntil;

ZmqAgentClientOptions FastOptions() {
  ZmqAgentClientOptions options;
  options.heartbeat_interval = std::chrono::milliseconds(100);
  options.link_timeout = std::chrono::milliseconds(600);
  options.status_poll = std::chrono::milliseconds(50);
  return options;
}

std::unique_ptr<ZmqAgentClient> ConnectedClient(const FakeAgent& agent) {
  auto client = std::make_unique<ZmqAgentClient>(FastOptions());
  EXPECT_TRUE(client->connectToEndpoints(QString::fromStdString(agent.command_endpoint),
                                         QString::fromStdString(agent.stream_endpoint)));
  EXPECT_TRUE(WaitUntil([&] { return client->linkState().up; }));
  return client;
}

TEST(ZmqAgentClient, ConnectsAndShowsTheLinkUpWithTheAgentsId) {
  FakeAgent agent;
  auto client = ConnectedClient(agent);
  EXPECT_EQ(client->linkState().agent_id, QString::fromLatin1(kapfix::testing::kAgentId));
  EXPECT_TRUE(WaitUntil([&] { return client->linkState().latency_us >= 0; }));
}

TEST(ZmqAgentClient, SspResultsArriveOnTheGuiThread) {
  FakeAgent agent;
  auto client = ConnectedClient(agent);
  kapfix::v1::SliceReport finished;
  QObject::connect(client.get(), &AgentClient::sliceReportReceived,
                   [&finished](const kapfix::v1::SliceReport& report) {
                     EXPECT_EQ(QThread::currentThread(), QCoreApplication::instance()->thread());
                     if (report.finished()) finished = report;
                   });
  kapfix::v1::Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  bool ok = false;
  client->sendCommand(command, [&ok](const CommandOutcome& outcome) { ok = outcome.ok; });
  ASSERT_TRUE(WaitUntil([&] { return finished.finished(); }));
  EXPECT_TRUE(ok);
  EXPECT_EQ(finished.recommended_slice(), kapfix::testing::FakeAgentControl::kRecommendedSlice);
}

TEST(ZmqAgentClient, RefusedCommandReportsTheAgentsReason) {
  FakeAgent agent;
  agent.control.RefuseWith(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, "p must be finite");
  auto client = ConnectedClient(agent);
  std::optional<CommandOutcome> seen;
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_p(1.0F);
  client->sendCommand(command, [&seen](const CommandOutcome& outcome) { seen = outcome; });
  ASSERT_TRUE(WaitUntil([&] { return seen.has_value(); }));
  EXPECT_TRUE(seen->answered);
  EXPECT_FALSE(seen->ok);
  EXPECT_EQ(seen->reason, QStringLiteral("p must be finite"));
}

TEST(ZmqAgentClient, LinkLossShowsWithinTheTimeoutWhileTheGuiKeepsRunning) {
  auto agent = std::make_unique<FakeAgent>();
  auto client = ConnectedClient(*agent);
  // A GUI timer must keep ticking while the link dies: nothing may block the event loop.
  int ticks = 0;
  QTimer tick;
  QObject::connect(&tick, &QTimer::timeout, [&ticks] { ++ticks; });
  tick.start(10);
  QElapsedTimer since_loss;
  agent.reset();
  since_loss.start();
  ASSERT_TRUE(WaitUntil([&] { return !client->linkState().up; }));
  EXPECT_LT(since_loss.elapsed(), 600 + 500);  // link_timeout plus the status poll, with room
  EXPECT_GT(ticks, static_cast<int>(since_loss.elapsed() / 10 / 4));
  std::optional<CommandOutcome> seen;
  client->sendCommand(kapfix::v1::Command{}, [&seen](const CommandOutcome& o) { seen = o; });
  ASSERT_TRUE(WaitUntil([&] { return seen.has_value(); }, std::chrono::milliseconds(5000)));
  EXPECT_FALSE(seen->answered);
}

TEST(ZmqAgentClient, PhotoChunksArriveFromTheAgent) {
  FakeAgent agent;
  auto client = ConnectedClient(agent);
  std::size_t bytes = 0;
  QObject::connect(client.get(), &AgentClient::photoChunkReceived,
                   [&bytes](const kapfix::v1::Photo& chunk) { bytes += chunk.data().size(); });
  kapfix::v1::Command command;
  command.mutable_take_photo();
  client->sendCommand(command);
  EXPECT_TRUE(
      WaitUntil([&] { return bytes == kapfix::testing::FakeAgentControl::PhotoBytes().size(); }));
}

}  // namespace
}  // namespace kapfix::station
