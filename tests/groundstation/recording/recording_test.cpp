#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QDir>
#include <QTemporaryDir>
#include <QTest>
#include <utility>
#include <vector>

#include "groundstation/client/fake_agent_client.hpp"
#include "groundstation/client/switchable_agent_client.hpp"
#include "groundstation/main_window.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/plots/telemetry_plots.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/recording/replay_agent_client.hpp"
#include "groundstation/recording/session_recording.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeSliceReport;
using testing::MakeTelemetry;
using testing::ProcessEvents;
using Curve = TelemetryPlots::Curve;

std::vector<double> Values(const TelemetryPlots& plots, Curve curve) {
  std::vector<double> values;
  const QCPGraph* graph = plots.graph(curve);
  for (int i = 0; i < graph->dataCount(); ++i) values.push_back(graph->data()->at(i)->value);
  return values;
}

TEST(Recording, RecordThenReplayShowsTheSameTelemetryInThePlots) {
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("s.kfxrec"));
  FakeAgentClient live;
  RecordingControls controls(live);
  TelemetryPlots plots(live);

  ASSERT_TRUE(controls.startRecording(path));
  for (int i = 0; i < 20; ++i)
    live.publish(MakeTelemetry(i, i * 3 - 10, 2 - i, 1'000'000 + i * 40'000));
  controls.stopRecording();
  plots.redraw();
  const std::vector<double> live_x = Values(plots, Curve::kDisplacementX);
  const std::vector<double> live_y = Values(plots, Curve::kDisplacementY);
  ASSERT_EQ(live_x.size(), 20U);

  TelemetryPlots replayed(controls.replay());
  ASSERT_TRUE(controls.startReplay(path));
  controls.replay().playToEnd();
  replayed.redraw();
  plots.redraw();
  EXPECT_EQ(Values(replayed, Curve::kDisplacementX), live_x);
  EXPECT_EQ(Values(replayed, Curve::kDisplacementY), live_y);
  EXPECT_TRUE(controls.replaying());
  // The live graphs saw nothing of it.
  EXPECT_EQ(Values(plots, Curve::kDisplacementX), live_x);
}

TEST(Recording, CtrlRRecordsIntoThePhotosFolderUnderAnAutomaticName) {
  const QTemporaryDir photos;
  FakeAgentClient live;
  auto* controls = new RecordingControls(live);
  MainWindow window({&live, nullptr, controls});
  window.photos().setFolder(photos.path());
  window.show();
  window.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
  QTest::keyClick(&window, Qt::Key_R, Qt::ControlModifier);  // no dialog: it would block here
  ASSERT_TRUE(controls->recording().recording());
  live.publish(MakeTelemetry(1, 0, 0, 1'000'000));
  QTest::keyClick(&window, Qt::Key_R, Qt::ControlModifier);
  EXPECT_FALSE(controls->recording().recording());
  const QStringList files =
      QDir(photos.path()).entryList({QStringLiteral("session-*.kfxrec")}, QDir::Files);
  ASSERT_EQ(files.size(), 1);
  EXPECT_EQ(controls->messageText(), QStringLiteral("Recorded ") + files.front());
}

TEST(Recording, ReplayOpensItsOwnWindowAndLeavesTheLiveViewsAlone) {
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("s.kfxrec"));
  {
    FakeAgentClient source;
    SessionRecording recording(source);
    ASSERT_TRUE(recording.start(path));
    source.publish(MakeSliceReport(9, 6));
    for (int i = 0; i < 10; ++i) source.publish(MakeTelemetry(i, 5, 0, 1'000'000 + i * 40'000));
  }
  FakeAgentClient live;
  auto* controls = new RecordingControls(live);
  MainWindow window({&live, nullptr, controls});
  ASSERT_TRUE(controls->startReplay(path));
  controls->replay().playToEnd();
  ASSERT_NE(window.replayWindow(), nullptr);
  MainWindow& replay = *window.replayWindow();
  replay.plots().redraw();
  window.plots().redraw();
  EXPECT_EQ(replay.ssp().table().rowCount(), 9);
  EXPECT_EQ(replay.plots().series().samples().size(), 10U);
  EXPECT_TRUE(replay.windowTitle().contains(QStringLiteral("REPLAY")));
  EXPECT_EQ(window.ssp().table().rowCount(), 0);
  EXPECT_TRUE(window.plots().series().samples().empty());
  EXPECT_FALSE(window.status().linkText() == QStringLiteral("REPLAY"));
  // Closing its window ends the replay.
  replay.close();
  EXPECT_TRUE(testing::WaitUntil([&] { return window.replayWindow() == nullptr; }));
  EXPECT_FALSE(controls->replaying());
}

TEST(Recording, ReplayShowsTheRecordedSspResultsInTheSspPanel) {
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("s.kfxrec"));
  FakeAgentClient live;
  SwitchableAgentClient views(live);
  SessionRecording recording(views);
  ASSERT_TRUE(recording.start(path));
  live.publish(MakeSliceReport(9, 6));
  recording.stop();

  ReplayAgentClient replay;
  ASSERT_TRUE(replay.open(path));
  views.setSource(replay);
  SspPanel panel(views);
  replay.playToEnd();
  EXPECT_EQ(panel.recommended(), 6U);
  EXPECT_EQ(panel.table().rowCount(), 9);
}

TEST(Recording, CommandsAndRepliesAreRecordedAsEvents) {
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("s.kfxrec"));
  FakeAgentClient live;
  SessionRecording recording(live);
  ASSERT_TRUE(recording.start(path));
  kapfix::v1::Command command;
  command.set_select_slice(4);
  live.sendCommand(command);
  ProcessEvents();
  recording.stop();

  ReplayAgentClient replay;
  std::vector<std::uint32_t> slices;
  int replies = 0;
  QObject::connect(&replay, &AgentClient::commandSent,
                   [&slices](const kapfix::v1::Command& c) { slices.push_back(c.select_slice()); });
  QObject::connect(&replay, &AgentClient::replyReceived,
                   [&replies](const kapfix::v1::Reply& /*reply*/) { ++replies; });
  ASSERT_TRUE(replay.open(path));
  replay.playToEnd();
  EXPECT_EQ(slices, std::vector<std::uint32_t>{4});
  EXPECT_EQ(replies, 1);
}

// Two telemetry messages recorded 300 ms apart, replayed on a clock the test moves: the
// second one is due 300 ms after the first, at speed 1, and 150 ms after it at speed 2.
class ReplayPace : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = dir_.filePath(QStringLiteral("s.kfxrec"));
    // The bytes as a fake agent sends them, recorded with receive times set by the test.
    FakeAgentClient source;
    std::vector<std::pair<QString, QByteArray>> sent;
    QObject::connect(&source, &AgentClient::messageReceived,
                     [&sent](const QString& topic, const QByteArray& payload, qint64 /*t_us*/) {
                       sent.emplace_back(topic, payload);
                     });
    source.publish(MakeTelemetry(1, 0, 0, 1));
    source.publish(MakeTelemetry(2, 0, 0, 2));
    ASSERT_EQ(sent.size(), 2U);
    FakeAgentClient live;
    SessionRecording recording(live);
    ASSERT_TRUE(recording.start(path_));
    emit live.messageReceived(sent[0].first, sent[0].second, kFirstUs);
    emit live.messageReceived(sent[1].first, sent[1].second, kFirstUs + 300'000);
  }
  // Moves the replay's clock to `ms` after play() and lets the replay look at it.
  void At(ReplayAgentClient& replay, std::int64_t ms) {
    now_ns_ = ms * 1'000'000;
    replay.advance();
  }

  static constexpr std::int64_t kFirstUs = 1'700'000'000'000'000;
  QTemporaryDir dir_;
  QString path_;
  std::int64_t now_ns_ = 0;
  ReplayAgentClient::Clock clock_ = [this] { return now_ns_; };
};

TEST_F(ReplayPace, TheSecondMessageComesAtItsRecordedDelay) {
  ReplayAgentClient replay(clock_);
  ASSERT_TRUE(replay.open(path_));
  replay.play();
  At(replay, 0);
  EXPECT_EQ(replay.delivered(), 1U);
  At(replay, 299);
  EXPECT_EQ(replay.delivered(), 1U) << "the second message is 300 ms later";
  At(replay, 300);
  EXPECT_EQ(replay.delivered(), 2U);
  EXPECT_TRUE(replay.atEnd());
}

TEST_F(ReplayPace, TwiceTheSpeedHalvesTheDelay) {
  ReplayAgentClient replay(clock_);
  ASSERT_TRUE(replay.open(path_));
  replay.setSpeed(2.0);
  replay.play();
  At(replay, 149);
  EXPECT_EQ(replay.delivered(), 1U);
  At(replay, 150);
  EXPECT_EQ(replay.delivered(), 2U);
}

TEST_F(ReplayPace, NothingIsDeliveredWhilePaused) {
  ReplayAgentClient replay(clock_);
  ASSERT_TRUE(replay.open(path_));
  replay.play();
  At(replay, 100);
  replay.pause();
  At(replay, 10'000);
  EXPECT_EQ(replay.delivered(), 1U);
  EXPECT_DOUBLE_EQ(replay.positionS(), 0.1);
}

// The playback timer, not the test, moves playback on (on the steady clock): both messages
// arrive (waited for as an event).
TEST(Recording, ReplayPlaysOnByItself) {
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("s.kfxrec"));
  {
    FakeAgentClient live;
    SessionRecording recording(live);
    ASSERT_TRUE(recording.start(path));
    live.publish(MakeTelemetry(1, 0, 0, 1));
    live.publish(MakeTelemetry(2, 0, 0, 2));
  }
  ReplayAgentClient replay;
  ASSERT_TRUE(replay.open(path));
  replay.play();
  EXPECT_TRUE(testing::WaitUntil([&] { return replay.atEnd(); }));
  EXPECT_EQ(replay.delivered(), 2U);
}

TEST(Recording, ReplayRefusesCommandsWithItsReason) {
  ReplayAgentClient replay;
  std::optional<CommandOutcome> seen;
  replay.sendCommand(kapfix::v1::Command{}, [&seen](const CommandOutcome& o) { seen = o; });
  ProcessEvents();
  ASSERT_TRUE(seen.has_value());
  EXPECT_FALSE(seen->ok);
  EXPECT_TRUE(seen->reason.contains(QStringLiteral("no agent")));
}

TEST(Recording, NotARecordingIsRefusedWhenOpened) {
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("junk"));
  QFile junk(path);
  ASSERT_TRUE(junk.open(QIODevice::WriteOnly));
  junk.write("hello");
  junk.close();
  ReplayAgentClient replay;
  QString error;
  EXPECT_FALSE(replay.open(path, &error));
  EXPECT_FALSE(error.isEmpty());
}

}  // namespace
}  // namespace kapfix::station
