#include "groundstation/main_window.hpp"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QHeaderView>
#include <QLabel>
#include <QSettings>
#include <QStatusBar>
#include <QStyle>
#include <QTabBar>
#include <QTemporaryDir>
#include <QTest>

#include "groundstation/client/fake_agent_client.hpp"
#include "groundstation/events/event_log.hpp"
#include "groundstation/keys/lock_confirmation.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/plots/telemetry_plots.hpp"
#include "groundstation/session/session_banner.hpp"
#include "groundstation/session/session_tracker.hpp"
#include "groundstation/settings/setting_row.hpp"
#include "groundstation/settings/settings_panel.hpp"
#include "groundstation/settings/settings_reapply_offer.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "groundstation/status/lock_indicator.hpp"
#include "groundstation/status/lock_monitor.hpp"
#include "groundstation/video/video_panel.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeSliceReport;
using testing::MakeTelemetry;
using testing::MakeVideoFrame;
using testing::ProcessEvents;

constexpr std::int64_t kFrameUs = 33'333;  // [µs] 30 fps

LinkState Up() {
  LinkState state;
  state.up = true;
  state.source = QStringLiteral("fake");
  return state;
}

LinkState Down() {
  LinkState state;
  state.source = QStringLiteral("fake");
  return state;
}

// The agent fixating: `frames` telemetry messages with a residual of `x_px`.
void Fixate(FakeAgentClient& client, int first, int frames, int x_px, bool lock_lost = false) {
  for (int i = first; i < first + frames; ++i) {
    kapfix::v1::Telemetry telemetry = MakeTelemetry(i, x_px, 0, 1'000'000 + i * kFrameUs);
    telemetry.set_lock_lost(lock_lost);
    client.publish(telemetry);
  }
}

void ShowActive(MainWindow& window) {
  window.show();
  window.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
}

// Where `widget` is, in the window's coordinates.
QRect InWindow(const QWidget& widget, const QWidget& window) {
  return {widget.mapTo(&window, QPoint(0, 0)), widget.size()};
}

TEST(MainWindow, SpaceInTheWindowTakesAPhoto) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  QTest::keyClick(&window, Qt::Key_Space);
  EXPECT_NE(client.lastCommand(kapfix::v1::Command::kTakePhoto), nullptr);
}

TEST(MainWindow, SpaceInAFocusedNumberFieldTakesAPhotoAndKeepsTheValue) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  window.findChild<QDockWidget*>(QStringLiteral("photosDock"))->raise();
  QDoubleSpinBox& seconds = window.photos().intervalSeconds();
  seconds.setValue(12.5);
  seconds.setFocus();
  ASSERT_TRUE(testing::WaitUntil([&] { return seconds.hasFocus(); }));
  QTest::keyClick(&seconds, Qt::Key_Space);
  EXPECT_NE(client.lastCommand(kapfix::v1::Command::kTakePhoto), nullptr);
  EXPECT_DOUBLE_EQ(seconds.value(), 12.5);
  EXPECT_EQ(seconds.text(), QStringLiteral("12.5 s"));
}

TEST(MainWindow, F5StartsSspAtOnceWhenNoLockIsHeld) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  QTest::keyClick(&window, Qt::Key_F5);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetMode);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_mode().mode(), kapfix::v1::MODE_SSP);
}

TEST(MainWindow, F5WhileFixatingWaitsForEnter) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  Fixate(client, 1, 3, 1);
  QTest::keyClick(&window, Qt::Key_F5);
  EXPECT_EQ(client.lastCommand(kapfix::v1::Command::kSetMode), nullptr);
  EXPECT_TRUE(window.banner().text().contains(QStringLiteral("Enter")));
  QTest::keyClick(&window, Qt::Key_Return);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetMode);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_mode().mode(), kapfix::v1::MODE_SSP);
  EXPECT_FALSE(window.confirmation().pending());
}

TEST(MainWindow, EnterInAFocusedNumberFieldAnswersTheQuestion) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  window.findChild<QDockWidget*>(QStringLiteral("photosDock"))->raise();
  QDoubleSpinBox& seconds = window.photos().intervalSeconds();
  seconds.setFocus();
  ASSERT_TRUE(testing::WaitUntil([&] { return seconds.hasFocus(); }));
  Fixate(client, 1, 3, 1);
  QTest::keyClick(&seconds, Qt::Key_F5);
  ASSERT_TRUE(window.confirmation().pending());
  QTest::keyClick(&seconds, Qt::Key_Return);
  EXPECT_NE(client.lastCommand(kapfix::v1::Command::kSetMode), nullptr);
}

TEST(MainWindow, EscapeCancelsTheQuestion) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  Fixate(client, 1, 3, 1);
  QTest::keyClick(&window, Qt::Key_F5);
  QTest::keyClick(&window, Qt::Key_Escape);
  QTest::keyClick(&window, Qt::Key_Return);
  EXPECT_EQ(client.lastCommand(kapfix::v1::Command::kSetMode), nullptr);
}

TEST(MainWindow, ClickOnTheVideoWhileFixatingWaitsForEnter) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  window.resize(1366, 768);
  ShowActive(window);
  client.publish(MakeVideoFrame(640, 480, 9));
  Fixate(client, 1, 3, 1);
  ProcessEvents();
  VideoView& view = window.video().view();
  QTest::mouseClick(&view, Qt::LeftButton, {}, view.sliceCentre(3).toPoint());
  EXPECT_EQ(client.lastCommand(kapfix::v1::Command::kSelectSlice), nullptr);
  QTest::keyClick(&window, Qt::Key_Return);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSelectSlice);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->select_slice(), 3U);
}

TEST(MainWindow, LockIndicatorGoesLostWhenTheLockIsLost) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  client.setLink(Up());
  Fixate(client, 1, 30, 1);
  EXPECT_EQ(window.lockInStatusBar().verdictText(), QStringLiteral("LOCKED"));
  EXPECT_EQ(window.lockOnVideo().verdictText(), QStringLiteral("LOCKED"));
  EXPECT_TRUE(window.lockInStatusBar().text().contains(QStringLiteral("RMS 1.0 px")));
  Fixate(client, 31, 1, 40, /*lock_lost=*/true);
  EXPECT_EQ(window.lockInStatusBar().verdictText(), QStringLiteral("LOST"));
  EXPECT_EQ(window.lockOnVideo().verdictText(), QStringLiteral("LOST"));
  EXPECT_EQ(window.lock().alerts(), 1);
}

TEST(MainWindow, LinkDownMarksTheVideoStaleAndGreysTheLiveValues) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  client.setLink(Up());
  client.publish(MakeVideoFrame(640, 480, 9));
  Fixate(client, 1, 3, 1);
  EXPECT_TRUE(window.video().view().staleText().isEmpty());
  EXPECT_FALSE(window.status().valuesGreyed());
  client.setLink(Down());
  EXPECT_TRUE(window.video().view().staleText().startsWith(QStringLiteral("STALE: last frame")));
  EXPECT_TRUE(window.status().valuesGreyed());
  EXPECT_TRUE(window.lockInStatusBar().text().contains(QStringLiteral("no link")));
  EXPECT_TRUE(window.banner().text().startsWith(QStringLiteral("LINK DOWN")));
  // A new frame is live again.
  client.setLink(Up());
  client.publish(MakeVideoFrame(640, 480, 9));
  EXPECT_TRUE(window.video().view().staleText().isEmpty());
}

TEST(MainWindow, RestartedAgentIsAnnouncedAndTheOldSessionCleared) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  ShowActive(window);
  client.setLink(Up());
  client.publish(MakeSliceReport(9, 8));
  window.ssp().pickSlice(8);
  ProcessEvents();
  ASSERT_EQ(window.ssp().messageText(), QStringLiteral("Fixating on slice 8"));
  Fixate(client, 1, 30, 2);
  window.plots().redraw();

  client.restartAgent();
  kapfix::v1::Telemetry idle = MakeTelemetry(1, 0, 0, 5'000'000);
  idle.set_mode(kapfix::v1::MODE_IDLE);
  client.publish(idle);
  window.plots().redraw();

  EXPECT_TRUE(window.banner().text().startsWith(QStringLiteral("AGENT RESTARTED")));
  EXPECT_EQ(window.ssp().table().rowCount(), 0);
  EXPECT_TRUE(window.ssp().messageText().isEmpty());
  EXPECT_EQ(window.plots().graph(TelemetryPlots::Curve::kDisplacementX)->dataCount(), 1);
  EXPECT_EQ(window.plots().series().session(), 2);
  EXPECT_FALSE(window.video().view().hasPicture());
  // Dismissed, it goes.
  ASSERT_TRUE(window.banner().dismissButton().isVisible());
  QTest::mouseClick(&window.banner().dismissButton(), Qt::LeftButton);
  EXPECT_TRUE(window.banner().text().isEmpty()) << window.banner().text().toStdString();
}

TEST(MainWindow, ARestartedAgentThatResumedIsAnnouncedAsResumed) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  client.setLink(Up());
  client.setBootId(11);
  Fixate(client, 1, 3, 1);
  client.restartAgent(12);
  kapfix::v1::AgentState state;
  state.set_mode(kapfix::v1::MODE_FIXATE);
  state.set_slice(8);
  state.set_resumed(true);
  client.publish(state);
  EXPECT_EQ(window.sessions().restarts(), 1);
  const QString banner = window.banner().text();
  EXPECT_TRUE(banner.startsWith(QStringLiteral("AGENT RESTARTED"))) << banner.toStdString();
  EXPECT_TRUE(banner.contains(QStringLiteral("RESUMED"))) << banner.toStdString();
  EXPECT_TRUE(banner.contains(QStringLiteral("slice 8"))) << banner.toStdString();
  EXPECT_TRUE(window.status().modeText().contains(QStringLiteral("resumed")))
      << window.status().modeText().toStdString();
}

// The operator's own settings of this run, not the agent's defaults, are what the station
// offers back after a restart; nothing is sent until the operator says so.
TEST(MainWindow, AfterARestartTheStationOffersToReapplyTheOperatorsDifferingSettings) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  client.setLink(Up());
  client.setBootId(21);
  Fixate(client, 1, 3, 1);
  auto* p = qobject_cast<QDoubleSpinBox*>(window.settings().row(QStringLiteral("p"))->editor());
  ASSERT_NE(p, nullptr);
  p->setValue(0.6);
  ProcessEvents();  // the fake accepts it
  const std::size_t sent = client.commands().size();

  client.restartAgent(22);
  kapfix::v1::AgentState state;
  state.mutable_gains()->set_p(1.0F);  // the restarted agent's default
  client.publish(state);
  const SettingsReapplyOffer& offer = window.reapplyOffer();
  EXPECT_FALSE(offer.isHidden());
  EXPECT_EQ(offer.keys(), QStringList{QStringLiteral("p")});
  EXPECT_TRUE(offer.text().contains(QStringLiteral("p is 1 (yours: 0.6)")))
      << offer.text().toStdString();
  EXPECT_EQ(client.commands().size(), sent) << "never re-applied by itself";

  offer.reapplyButton().click();
  ASSERT_EQ(client.commands().size(), sent + 1);
  ASSERT_TRUE(client.commands().back().has_set_gains());
  EXPECT_FLOAT_EQ(client.commands().back().set_gains().p(), 0.6F);
  EXPECT_EQ(window.settings().row(QStringLiteral("p"))->value(), QStringLiteral("0.6"));
  EXPECT_TRUE(offer.isHidden());
}

TEST(MainWindow, NoReapplyOfferWhenTheRestartedAgentKeptTheOperatorsSettings) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  client.setLink(Up());
  client.setBootId(31);
  Fixate(client, 1, 3, 1);
  auto* p = qobject_cast<QDoubleSpinBox*>(window.settings().row(QStringLiteral("p"))->editor());
  ASSERT_NE(p, nullptr);
  p->setValue(0.6);
  ProcessEvents();
  client.restartAgent(32);
  kapfix::v1::AgentState state;
  state.mutable_gains()->set_p(0.6F);  // resumed with the operator's gains
  client.publish(state);
  EXPECT_EQ(window.sessions().restarts(), 1);
  EXPECT_TRUE(window.reapplyOffer().isHidden());
}

TEST(MainWindow, FitsALaptopScreenWithTheVideoFirst) {
  QSettings().clear();
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  window.resize(1366, 768);
  ShowActive(window);
  client.publish(MakeVideoFrame(640, 480, 9));
  ProcessEvents();
  const QRect all(QPoint(0, 0), QSize(1366, 768));
  EXPECT_LE(window.width(), 1366);
  EXPECT_LE(window.height(), 768);
  const QRect video = InWindow(window.video().view(), window);
  const QRect status = InWindow(*window.statusBar(), window);
  auto* tabs = window.findChild<QTabBar*>();
  ASSERT_NE(tabs, nullptr);
  const QRect tab_bar = InWindow(*tabs, window);
  const QRect graphs = InWindow(window.plots(), window);
  for (const QRect& part : {video, status, tab_bar}) {
    EXPECT_TRUE(all.contains(part))
        << part.x() << "," << part.y() << " " << part.width() << "x" << part.height();
  }
  EXPECT_TRUE(tabs->isVisible());
  EXPECT_FALSE(video.intersects(status));
  EXPECT_FALSE(video.intersects(tab_bar));
  EXPECT_FALSE(video.intersects(graphs));
  EXPECT_FALSE(tab_bar.intersects(status));
  // The video gets the space first: more than half the width, more than a third of the height.
  EXPECT_GT(video.width(), 1366 / 2);
  EXPECT_GT(video.height(), 768 / 3);
  if (const QString dir = qEnvironmentVariable("KAPFIX_SCREENSHOT_DIR"); !dir.isEmpty()) {
    window.grab().save(dir + QStringLiteral("/station_1366x768.png"));
  }
}

// What a larger font cuts off in `window`: labels narrower than they need, tab titles and
// table headers shorter than their text, axis labels longer than their axis, tick labels
// that overlap. One line per finding.
// On screen now (not in a tab behind another, not scrolled away).
bool Shown(const QWidget& widget) {
  return widget.isVisible() && !widget.visibleRegion().isEmpty();
}

QStringList Truncated(const QWidget& window) {
  QStringList found;
  for (const QLabel* label : window.findChildren<QLabel*>()) {
    if (!Shown(*label) || label->text().isEmpty() || label->wordWrap()) continue;
    if (label->width() < label->minimumSizeHint().width()) {
      found << QStringLiteral("label '%1': %2 < %3 px")
                   .arg(label->text())
                   .arg(label->width())
                   .arg(label->minimumSizeHint().width());
    }
  }
  for (const QTabBar* tabs : window.findChildren<QTabBar*>()) {
    if (!Shown(*tabs)) continue;
    // A tab's text and the style's room around it (Qt elides the text in less).
    const int room = tabs->style()->pixelMetric(QStyle::PM_TabBarTabHSpace, nullptr, tabs);
    for (int i = 0; i < tabs->count(); ++i) {
      const int needed = tabs->fontMetrics().horizontalAdvance(tabs->tabText(i)) + room;
      if (tabs->tabRect(i).width() < needed) {
        found << QStringLiteral("tab '%1': %2 < %3 px")
                     .arg(tabs->tabText(i))
                     .arg(tabs->tabRect(i).width())
                     .arg(needed);
      }
    }
  }
  for (const QHeaderView* header : window.findChildren<QHeaderView*>()) {
    if (!Shown(*header) || header->orientation() != Qt::Horizontal) continue;
    for (int i = 0; i < header->count(); ++i) {
      const QString text = header->model()->headerData(i, Qt::Horizontal).toString();
      const int needed = header->fontMetrics().horizontalAdvance(text);
      if (!header->isSectionHidden(i) && header->sectionSize(i) < needed) {
        found << QStringLiteral("header '%1': %2 < %3 px")
                     .arg(text)
                     .arg(header->sectionSize(i))
                     .arg(needed);
      }
    }
  }
  for (QCustomPlot* plot : window.findChildren<QCustomPlot*>()) {
    if (!Shown(*plot)) continue;
    plot->replot(QCustomPlot::rpImmediateRefresh);
    for (QCPAxis* axis : plot->axisRect()->axes()) {
      if (!axis->visible()) continue;
      const bool vertical = axis->orientation() == Qt::Vertical;
      const int length = vertical ? axis->axisRect()->height() : axis->axisRect()->width();
      const QFontMetrics label_metrics(axis->labelFont());
      if (!axis->label().isEmpty() && label_metrics.horizontalAdvance(axis->label()) > length) {
        found << QStringLiteral("%1 axis label '%2': longer than its axis (%3 px)")
                     .arg(plot->parent()->metaObject()->className(), axis->label())
                     .arg(length);
      }
      if (!axis->tickLabels()) continue;
      // Neighbouring tick labels must not overlap: their distance on the axis is at least a
      // label's height (vertical) or half of each label's width plus a gap (horizontal).
      const QFontMetrics tick_metrics(axis->tickLabelFont());
      const QVector<double> ticks = axis->tickVector();
      const QVector<QString> labels = axis->tickVectorLabels();
      for (int t = 1; t < ticks.size() && t < labels.size(); ++t) {
        const double gap =
            std::abs(axis->coordToPixel(ticks[t]) - axis->coordToPixel(ticks[t - 1]));
        const double needed = vertical ? tick_metrics.height()
                                       : (tick_metrics.horizontalAdvance(labels[t - 1]) +
                                          tick_metrics.horizontalAdvance(labels[t])) /
                                                 2.0 +
                                             4;
        if (gap < needed) {
          found << QStringLiteral("%1 tick labels '%2' and '%3' overlap: %4 px apart, %5 needed")
                       .arg(plot->parent()->metaObject()->className(), labels[t - 1], labels[t])
                       .arg(gap, 0, 'f', 0)
                       .arg(needed, 0, 'f', 0);
        }
      }
    }
  }
  return found;
}

// Issue 14: a larger font (an operator's accessibility setting, a high-density screen)
// truncates nothing, and the window at 1366×768 still shows video, status bar and tabs.
TEST(MainWindow, ALargerFontTruncatesNothingAndTheWindowStillFitsALaptop) {
  QSettings().clear();
  const QFont normal = QApplication::font();
  QFont larger = normal;
  larger.setPointSizeF(normal.pointSizeF() * 1.5);
  QApplication::setFont(larger);
  {
    FakeAgentClient client;
    MainWindow window({&client, nullptr, nullptr});
    window.resize(1366, 768);
    ShowActive(window);
    client.setLink(Up());
    client.publish(MakeVideoFrame(640, 480, 9));
    client.publish(MakeSliceReport(9, 8));
    Fixate(client, 1, 60, 3);
    window.plots().redraw();
    ProcessEvents();
    for (const char* dock : {"sspDock", "settingsDock", "photosDock", "eventsDock"}) {
      window.findChild<QDockWidget*>(QLatin1String(dock))->raise();
      ProcessEvents();
      const QStringList truncated = Truncated(window);
      EXPECT_TRUE(truncated.isEmpty()) << dock << ":\n"
                                       << truncated.join(QLatin1Char('\n')).toStdString();
    }
    EXPECT_LE(window.width(), 1366);
    EXPECT_LE(window.height(), 768);
    const QRect all(QPoint(0, 0), window.size());
    const QRect video = InWindow(window.video().view(), window);
    const QRect status = InWindow(*window.statusBar(), window);
    auto* tabs = window.findChild<QTabBar*>();
    ASSERT_NE(tabs, nullptr);
    const QRect tab_bar = InWindow(*tabs, window);
    for (const QRect& part : {video, status, tab_bar}) EXPECT_TRUE(all.contains(part));
    EXPECT_FALSE(video.intersects(status));
    EXPECT_FALSE(video.intersects(tab_bar));
    EXPECT_GT(video.width(), 1366 / 2);
    EXPECT_GT(video.height(), 768 / 4);
    if (const QString dir = qEnvironmentVariable("KAPFIX_SCREENSHOT_DIR"); !dir.isEmpty()) {
      window.grab().save(dir + QStringLiteral("/station_1366x768_font150.png"));
    }
    window.close();
  }
  QApplication::setFont(normal);
  QSettings().clear();
}

TEST(MainWindow, LayoutIsRememberedBetweenRuns) {
  QSettings().clear();
  FakeAgentClient client;
  {
    MainWindow window({&client, nullptr, nullptr});
    window.resize(1111, 777);
    window.show();
    window.close();
  }
  const MainWindow again({&client, nullptr, nullptr});
  EXPECT_EQ(again.size(), QSize(1111, 777));
  QSettings().clear();
}

}  // namespace
}  // namespace kapfix::station
