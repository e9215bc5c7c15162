// Issue 5's link loss, seen from the station, against the real kapfix-agent in simulation:
// the status bar shows a dead link within 3.5 s, and a station that was closed and started
// again is resynchronised (settings, latest SSP result, photos taken meanwhile) within 2 s.
//
// A dead link is made by stopping the agent process (SIGSTOP): its TCP connections stay open
// and nothing more arrives, as when the WiFi goes out of range. "Killing the station" is done
// in-process: every station object is destroyed (its sockets close) and built again over the
// same photo folder, as a restarted kapfix-station would be.
#include <gtest/gtest.h>
#include <signal.h>

#include <QDir>
#include <QElapsedTimer>
#include <QSpinBox>
#include <QTemporaryDir>
#include <cstdio>
#include <fstream>
#include <memory>

#include "groundstation/client/link_resync.hpp"
#include "groundstation/client/zmq_agent_client.hpp"
#include "groundstation/main_window.hpp"
#include "groundstation/photos/photo_store.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "tests/groundstation/station_test_support.hpp"
#include "tests/integration/agent_process.hpp"

namespace kapfix::station {
namespace {

using testing::WaitUntil;

constexpr auto kLongWait = std::chrono::milliseconds(20000);
constexpr qint64 kLinkLossShownMs = 3500;  // issue 5
constexpr qint64 kResyncMs = 2000;         // issue 5

// A short SSP swing, and a photo every second so that photos pile up while no station runs.
std::string WriteConfig() {
  const auto path = std::filesystem::temp_directory_path() /
                    ("kapfix_station_link_loss_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << R"({"search": {"swing_frames": 45},
                             "settings": {"search": {"axis": "AXIS_BOTH"}, "gains": {"p": 1.0},
                                          "photo": {"interval_s": 1}}})";
  return path.string();
}

int JpegsIn(const std::filesystem::path& folder) {
  const QDir dir(QString::fromStdString(folder.string()));
  return static_cast<int>(dir.entryList({QStringLiteral("*.jpg")}, QDir::Files).size());
}

// One kapfix-station as main.cpp wires it, with the real station's link options.
struct Station {
  Station(const kapfix::testing::AgentProcess& agent, const QString& photos_folder)
      : recording(new RecordingControls(live)), window(MainWindowParts{&live, nullptr, recording}) {
    window.photos().setFolder(photos_folder);
    const std::int64_t newest = PhotoStore::newestCaptureTimeUs(photos_folder);
    resync = std::make_unique<LinkResync>(live, newest > 0 ? newest + 1 : kapfix::v1::NowMicros());
    QObject::connect(&live, &AgentClient::stateReceived,
                     [this](const kapfix::v1::AgentState& s) { state = s; });
    live.connectToEndpoints(QString::fromStdString(agent.command_endpoint()),
                            QString::fromStdString(agent.stream_endpoint()));
  }

  ZmqAgentClient live;           // default options: the link timeout an operator gets
  RecordingControls* recording;  // owned by the window
  MainWindow window;
  std::unique_ptr<LinkResync> resync;
  kapfix::v1::AgentState state;
};

class StationLinkLoss : public ::testing::Test {
 protected:
  StationLinkLoss() : agent_({"--config", WriteConfig(), "--mode", "idle"}) {}
  ~StationLinkLoss() override {
    if (agent_.pid() > 0) ::kill(agent_.pid(), SIGCONT);  // a stopped agent cannot exit
  }

  kapfix::testing::AgentProcess agent_;
  const QTemporaryDir photos_;
};

TEST_F(StationLinkLoss, DeadLinkIsShownWithinThreeAndAHalfSeconds) {
  Station station(agent_, photos_.path());
  ASSERT_TRUE(WaitUntil(
      [&] { return station.window.status().linkText() == QStringLiteral("LINK UP"); }, kLongWait))
      << agent_.log();
  ASSERT_EQ(::kill(agent_.pid(), SIGSTOP), 0);
  QElapsedTimer since_loss;
  since_loss.start();
  ASSERT_TRUE(
      WaitUntil([&] { return station.window.status().linkText() == QStringLiteral("LINK DOWN"); },
                kLongWait));
  const qint64 shown_ms = since_loss.elapsed();
  std::printf("link loss shown after %lld ms\n", static_cast<long long>(shown_ms));
  EXPECT_LT(shown_ms, kLinkLossShownMs);
  // And it comes back by itself once the agent is heard again.
  ASSERT_EQ(::kill(agent_.pid(), SIGCONT), 0);
  EXPECT_TRUE(WaitUntil(
      [&] { return station.window.status().linkText() == QStringLiteral("LINK UP"); }, kLongWait));
}

TEST_F(StationLinkLoss, RestartedStationIsResynchronisedWithinTwoSeconds) {
  kapfix::v1::SliceReport report;
  {
    Station first(agent_, photos_.path());
    ASSERT_TRUE(WaitUntil([&] { return first.live.linkState().up; }, kLongWait)) << agent_.log();
    kapfix::v1::Command gains;
    gains.mutable_set_gains()->set_p(0.75F);
    first.live.sendCommand(gains);
    first.window.ssp().findChild<QSpinBox*>()->setValue(45);
    first.window.ssp().runAction()->trigger();
    ASSERT_TRUE(WaitUntil([&] { return first.state.last_slice_report().finished(); }, kLongWait))
        << agent_.log();
    ASSERT_TRUE(WaitUntil([&] { return first.state.gains().p() == 0.75F; }, kLongWait));
    report = first.state.last_slice_report();
  }  // the station is gone; the agent flies on and keeps taking photos
  const int held_before = JpegsIn(photos_.path().toStdString());
  ASSERT_TRUE(WaitUntil([&] { return JpegsIn(agent_.photos()) >= held_before + 3; }, kLongWait))
      << "the agent took no photos while the station was away";
  const int on_agent = JpegsIn(agent_.photos());

  QElapsedTimer since_start;
  since_start.start();
  Station second(agent_, photos_.path());
  const bool resynchronised = WaitUntil(
      [&] {
        return second.state.gains().p() == 0.75F &&
               second.state.last_slice_report().recommended_slice() == report.recommended_slice() &&
               JpegsIn(photos_.path().toStdString()) >= on_agent;
      },
      kLongWait);
  const qint64 elapsed = since_start.elapsed();
  ASSERT_TRUE(resynchronised) << "held " << JpegsIn(photos_.path().toStdString()) << " of "
                              << on_agent << " photos";
  std::printf("resynchronised after %lld ms (%d photos)\n", static_cast<long long>(elapsed),
              on_agent - held_before);
  EXPECT_LT(elapsed, kResyncMs);
  EXPECT_TRUE(second.state.last_slice_report().finished());
}

}  // namespace
}  // namespace kapfix::station
