// The whole station against an agent on loopback (issue 4's list): connect, run SSP, pick a
// slice, change a gain, capture a photo, replay a recording. The agent is tests/link's
// FakeAgent — the agent's real CommandServer and StreamPublisher in front of a fake
// pipeline — until the real agent serves the link in simulation.
#include <gtest/gtest.h>

#include <QDoubleSpinBox>
#include <QFile>
#include <QTemporaryDir>
#include <memory>

#include "groundstation/client/link_resync.hpp"
#include "groundstation/client/zmq_agent_client.hpp"
#include "groundstation/main_window.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/settings/setting_row.hpp"
#include "groundstation/settings/settings_panel.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "tests/groundstation/station_test_support.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::station {
namespace {

using kapfix::testing::FakeAgent;
using kapfix::testing::FakeAgentControl;
using testing::WaitUntil;

class StationLoopback : public ::testing::Test {
 protected:
  StationLoopback() : live_(Options()) {
    recording_ = new RecordingControls(live_);
    window_ = std::make_unique<MainWindow>(MainWindowParts{&live_, nullptr, recording_});
    window_->photos().setFolder(photos_.path());
    live_.connectToEndpoints(QString::fromStdString(agent_.command_endpoint),
                             QString::fromStdString(agent_.stream_endpoint));
  }

  static ZmqAgentClientOptions Options() {
    ZmqAgentClientOptions options;
    options.heartbeat_interval = std::chrono::milliseconds(100);
    options.status_poll = std::chrono::milliseconds(50);
    return options;
  }

  bool CommandSeen(kapfix::v1::Command::CommandCase kind) {
    return WaitUntil([&] {
      for (const auto& command : agent_.control.commands()) {
        if (command.command_case() == kind) return true;
      }
      return false;
    });
  }

  FakeAgent agent_;
  const QTemporaryDir photos_;
  ZmqAgentClient live_;
  const LinkResync resync_{live_, kapfix::v1::NowMicros()};
  RecordingControls* recording_;  // owned by the window
  std::unique_ptr<MainWindow> window_;
};

TEST_F(StationLoopback, ConnectsAndShowsTheLinkUp) {
  EXPECT_TRUE(WaitUntil([&] { return window_->status().linkText() == QStringLiteral("LINK UP"); }));
  EXPECT_TRUE(CommandSeen(kapfix::v1::Command::kRequestState)) << "resynchronises on connect";
}

TEST_F(StationLoopback, RunsSspAndPicksTheRecommendedSlice) {
  ASSERT_TRUE(WaitUntil([&] { return live_.linkState().up; }));
  window_->ssp().runAction()->trigger();
  ASSERT_TRUE(WaitUntil(
      [&] { return window_->ssp().recommended() == FakeAgentControl::kRecommendedSlice; }));
  window_->ssp().confirmAction()->trigger();
  EXPECT_TRUE(WaitUntil(
      [&] { return agent_.control.State().slice() == FakeAgentControl::kRecommendedSlice; }));
}

TEST_F(StationLoopback, ChangesAGain) {
  ASSERT_TRUE(WaitUntil([&] { return live_.linkState().up; }));
  auto* p = qobject_cast<QDoubleSpinBox*>(window_->settings().row(QStringLiteral("p"))->editor());
  p->setValue(2.5);
  EXPECT_TRUE(WaitUntil([&] { return agent_.control.State().gains().p() == 2.5F; }));
  EXPECT_TRUE(WaitUntil([&] {
    return window_->settings().row(QStringLiteral("p"))->statusLabel()->text() ==
           QStringLiteral("✓");
  }));
}

TEST_F(StationLoopback, CapturesAPhotoIntoTheFolder) {
  ASSERT_TRUE(WaitUntil([&] { return live_.linkState().up; }));
  window_->photos().captureAction()->trigger();
  const QString path = photos_.filePath(QString::fromLatin1(FakeAgentControl::kPhotoName));
  ASSERT_TRUE(WaitUntil([&] { return QFile::exists(path); }));
  QFile file(path);
  ASSERT_TRUE(file.open(QIODevice::ReadOnly));
  EXPECT_EQ(file.readAll().toStdString(), FakeAgentControl::PhotoBytes());
  EXPECT_TRUE(QFile::exists(path + QStringLiteral(".json")));
}

TEST_F(StationLoopback, ReplaysARecordingOfTheLiveSession) {
  ASSERT_TRUE(WaitUntil([&] { return live_.linkState().up; }));
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("flight.kfxrec"));
  ASSERT_TRUE(recording_->startRecording(path));
  window_->ssp().runAction()->trigger();
  ASSERT_TRUE(WaitUntil([&] { return window_->ssp().recommended() > 0; }));
  recording_->stopRecording();

  agent_.control.RefuseWith(kapfix::v1::ERROR_CODE_INTERNAL, "must not be reached in replay");
  ASSERT_TRUE(recording_->startReplay(path));
  recording_->replay().playToEnd();
  ASSERT_NE(window_->replayWindow(), nullptr);  // a window of its own
  const MainWindow& replay = *window_->replayWindow();
  EXPECT_EQ(replay.status().linkText(), QStringLiteral("REPLAY"));
  EXPECT_EQ(replay.ssp().table().rowCount(), 9);
  EXPECT_EQ(replay.ssp().recommended(), FakeAgentControl::kRecommendedSlice);
  recording_->backToLive();
  EXPECT_TRUE(WaitUntil([&] { return window_->status().linkText() == QStringLiteral("LINK UP"); }));
}

}  // namespace
}  // namespace kapfix::station
