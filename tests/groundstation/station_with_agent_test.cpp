// The whole station against the real kapfix-agent in simulation on loopback (issue 4's list):
// connect, run SSP, pick a slice, change a gain, capture a photo, replay a recording. The agent
// runs as a child process (tests/integration/agent_process.hpp) flying the kite over aero1.jpg
// in real time; the SSP panel asks for a free swing of 45 frames so that a test takes seconds.
#include <gtest/gtest.h>
#include <signal.h>

#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QSpinBox>
#include <QTemporaryDir>
#include <cstdio>
#include <fstream>
#include <memory>

#include "groundstation/client/link_resync.hpp"
#include "groundstation/client/zmq_agent_client.hpp"
#include "groundstation/main_window.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/session/session_banner.hpp"
#include "groundstation/settings/setting_row.hpp"
#include "groundstation/settings/settings_panel.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/device_health_view.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "groundstation/video/video_panel.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "tests/groundstation/station_test_support.hpp"
#include "tests/integration/agent_process.hpp"

namespace kapfix::station {
namespace {

using testing::WaitUntil;

constexpr auto kLongWait = std::chrono::milliseconds(20000);
constexpr qint64 kStaleShownMs = 3500;  // [ms] issue 14: a dead agent is seen within this

// The built-in simulation's choices (BuiltInConfig) with a short SSP swing.
std::string WriteConfig() {
  const auto path = std::filesystem::temp_directory_path() /
                    ("kapfix_station_agent_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << R"({"search": {"swing_frames": 45},
                             "settings": {"search": {"axis": "AXIS_BOTH"}, "gains": {"p": 1.0}}})";
  return path.string();
}

class StationWithAgent : public ::testing::Test {
 protected:
  StationWithAgent() : agent_({"--config", WriteConfig(), "--mode", "idle"}), live_(Options()) {
    recording_ = new RecordingControls(live_);
    window_ = std::make_unique<MainWindow>(MainWindowParts{&live_, nullptr, recording_});
    window_->photos().setFolder(photos_.path());
    QObject::connect(&live_, &AgentClient::stateReceived,
                     [this](const kapfix::v1::AgentState& state) { state_ = state; });
    QObject::connect(&live_, &AgentClient::telemetryReceived,
                     [this](const kapfix::v1::Telemetry& /*telemetry*/) { ++telemetry_; });
    live_.connectToEndpoints(QString::fromStdString(agent_.command_endpoint()),
                             QString::fromStdString(agent_.stream_endpoint()));
  }

  static ZmqAgentClientOptions Options() {
    ZmqAgentClientOptions options;
    options.heartbeat_interval = std::chrono::milliseconds(100);
    options.status_poll = std::chrono::milliseconds(50);
    return options;
  }

  kapfix::testing::AgentProcess agent_;
  const QTemporaryDir photos_;
  ZmqAgentClient live_;
  const LinkResync resync_{live_, kapfix::v1::NowMicros()};
  RecordingControls* recording_;  // owned by the window
  std::unique_ptr<MainWindow> window_;
  kapfix::v1::AgentState state_;  // the latest the agent published or replied
  int telemetry_ = 0;             // telemetry messages received

  // The streams flow: the subscription reached the agent, so nothing it publishes from now on
  // is missed (a PUB drops what it sends before a subscriber is connected).
  bool StreamsFlow() {
    return WaitUntil([&] { return live_.linkState().up && telemetry_ > 0; }, kLongWait);
  }
};

TEST_F(StationWithAgent, ConnectsAndShowsTheLinkUpAndTheAgentsMode) {
  ASSERT_TRUE(WaitUntil([&] { return window_->status().linkText() == QStringLiteral("LINK UP"); },
                        kLongWait))
      << agent_.log();
  EXPECT_TRUE(WaitUntil([&] { return state_.mode() == kapfix::v1::MODE_IDLE; }, kLongWait));
}

TEST_F(StationWithAgent, RunsSspPicksTheRecommendedSliceAndFixates) {
  ASSERT_TRUE(StreamsFlow()) << agent_.log();
  auto* deadline = window_->ssp().findChild<QSpinBox*>();
  ASSERT_NE(deadline, nullptr);
  deadline->setValue(45);  // [frames] of free swing: 1.5 s
  window_->ssp().runAction()->trigger();
  ASSERT_TRUE(WaitUntil(
      [&] {
        return state_.last_slice_report().finished() && state_.mode() == kapfix::v1::MODE_IDLE;
      },
      kLongWait))
      << agent_.log();
  EXPECT_EQ(window_->ssp().table().rowCount(), 9);
  const int recommended = window_->ssp().recommended();
  EXPECT_EQ(recommended, static_cast<int>(state_.last_slice_report().recommended_slice()));
  window_->ssp().confirmAction()->trigger();
  EXPECT_TRUE(WaitUntil(
      [&] {
        return state_.slice() == static_cast<unsigned>(recommended) &&
               state_.mode() == kapfix::v1::MODE_FIXATE;
      },
      kLongWait))
      << agent_.log();
}

TEST_F(StationWithAgent, ShowsTheSimulatedCameraAndServosAsOk) {
  ASSERT_TRUE(StreamsFlow()) << agent_.log();
  EXPECT_TRUE(WaitUntil(
      [&] {
        return window_->devices().cameraText() == QStringLiteral("Camera OK") &&
               window_->devices().servoText() == QStringLiteral("Servos OK");
      },
      kLongWait))
      << window_->devices().cameraText().toStdString() << " / "
      << window_->devices().servoText().toStdString();
  EXPECT_FALSE(window_->devices().anyLost());
}

TEST_F(StationWithAgent, ChangesAGain) {
  ASSERT_TRUE(StreamsFlow()) << agent_.log();
  auto* p = qobject_cast<QDoubleSpinBox*>(window_->settings().row(QStringLiteral("p"))->editor());
  p->setValue(0.75);
  EXPECT_TRUE(WaitUntil(
      [&] {
        return window_->settings().row(QStringLiteral("p"))->statusLabel()->text() ==
               QStringLiteral("✓");
      },
      kLongWait));
  EXPECT_TRUE(WaitUntil([&] { return state_.gains().p() == 0.75F; }, kLongWait));
}

TEST_F(StationWithAgent, CapturesAPhotoIntoTheFolderWithItsSidecar) {
  ASSERT_TRUE(StreamsFlow()) << agent_.log();
  window_->photos().captureAction()->trigger();
  const QDir folder(photos_.path());
  ASSERT_TRUE(
      WaitUntil([&] { return !folder.entryList({QStringLiteral("*.jpg")}, QDir::Files).isEmpty(); },
                kLongWait))
      << agent_.log();
  const QString name = folder.entryList({QStringLiteral("*.jpg")}, QDir::Files).front();
  EXPECT_TRUE(QFile::exists(folder.filePath(name + QStringLiteral(".json"))));
  // The same bytes as the agent's own copy.
  const auto on_agent = agent_.photos() / name.toStdString();
  ASSERT_TRUE(std::filesystem::exists(on_agent));
  EXPECT_EQ(QFileInfo(folder.filePath(name)).size(),
            static_cast<qint64>(std::filesystem::file_size(on_agent)));
}

TEST_F(StationWithAgent, ReplaysARecordingOfTheLiveSession) {
  ASSERT_TRUE(StreamsFlow()) << agent_.log();
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("flight.kfxrec"));
  ASSERT_TRUE(recording_->startRecording(path));
  window_->ssp().findChild<QSpinBox*>()->setValue(45);
  window_->ssp().runAction()->trigger();
  ASSERT_TRUE(WaitUntil([&] { return state_.last_slice_report().finished(); }, kLongWait));
  const int recommended = window_->ssp().recommended();
  recording_->stopRecording();
  agent_.Stop();  // replay needs no agent

  ASSERT_TRUE(recording_->startReplay(path));
  recording_->replay().playToEnd();
  ASSERT_NE(window_->replayWindow(), nullptr);  // a window of its own
  const MainWindow& replay = *window_->replayWindow();
  EXPECT_EQ(replay.status().linkText(), QStringLiteral("REPLAY"));
  EXPECT_EQ(replay.ssp().table().rowCount(), 9);
  EXPECT_EQ(replay.ssp().recommended(), recommended);
}

TEST_F(StationWithAgent, KilledAgentShowsTheStaleVideoWithinThreeAndAHalfSeconds) {
  ASSERT_TRUE(StreamsFlow()) << agent_.log();
  ASSERT_TRUE(WaitUntil([&] { return window_->video().view().hasPicture(); }, kLongWait));
  ASSERT_TRUE(window_->video().view().staleText().isEmpty());
  ASSERT_EQ(::kill(agent_.pid(), SIGKILL), 0);  // kill -9: no goodbye on the link
  QElapsedTimer since_kill;
  since_kill.start();
  ASSERT_TRUE(WaitUntil([&] { return !window_->video().view().staleText().isEmpty(); }, kLongWait));
  const qint64 shown_ms = since_kill.elapsed();
  std::printf("stale video shown after %lld ms: %s\n", static_cast<long long>(shown_ms),
              window_->video().view().staleText().toUtf8().constData());
  EXPECT_LT(shown_ms, kStaleShownMs);
  EXPECT_TRUE(window_->video().view().staleText().startsWith(QStringLiteral("STALE")));
  EXPECT_TRUE(window_->status().valuesGreyed());
  EXPECT_TRUE(window_->banner().text().startsWith(QStringLiteral("LINK DOWN")));
}

}  // namespace
}  // namespace kapfix::station
