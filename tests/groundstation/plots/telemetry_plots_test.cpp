#include "groundstation/plots/telemetry_plots.hpp"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QFile>
#include <QMouseEvent>
#include <QTemporaryDir>
#include <map>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeTelemetry;
using Curve = TelemetryPlots::Curve;

TEST(TelemetryPlots, TelemetryFromTheAgentReachesTheGraphs) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  client.publish(MakeTelemetry(1, 5, -2, 1'000'000));
  client.publish(MakeTelemetry(2, 7, -4, 1'500'000));
  plots.redraw();
  QCPGraph* x = plots.graph(Curve::kDisplacementX);
  ASSERT_EQ(x->dataCount(), 2);
  EXPECT_DOUBLE_EQ(x->data()->at(1)->key, 0.5);  // [s] since the first sample
  EXPECT_DOUBLE_EQ(x->data()->at(1)->value, 7);
  EXPECT_DOUBLE_EQ(plots.graph(Curve::kDisplacementY)->data()->at(1)->value, -4);
  EXPECT_DOUBLE_EQ(plots.graph(Curve::kConfidence)->data()->at(0)->value, 0.75);
  EXPECT_DOUBLE_EQ(plots.graph(Curve::kPan)->data()->at(0)->value, 1.5);
}

TEST(TelemetryPlots, PausedGraphsHoldStillAndCatchUpOnResume) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  client.publish(MakeTelemetry(1, 1, 0, 1'000'000));
  plots.redraw();
  plots.pauseAction()->setChecked(true);
  client.publish(MakeTelemetry(2, 2, 0, 1'100'000));
  plots.redraw();
  EXPECT_EQ(plots.graph(Curve::kDisplacementX)->dataCount(), 1);
  plots.pauseAction()->setChecked(false);
  EXPECT_EQ(plots.graph(Curve::kDisplacementX)->dataCount(), 2);
}

TEST(TelemetryPlots, CsvExportHoldsEverySampleWithUnits) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  client.publish(MakeTelemetry(1, 5, -2, 1'000'000));
  client.publish(MakeTelemetry(2, 7, -4, 1'500'000));
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("t.csv"));
  ASSERT_TRUE(plots.exportCsv(path));
  QFile file(path);
  ASSERT_TRUE(file.open(QIODevice::ReadOnly));
  const QStringList lines = QString::fromUtf8(file.readAll()).split('\n', Qt::SkipEmptyParts);
  ASSERT_EQ(lines.size(), 3);
  EXPECT_TRUE(lines[0].startsWith(QStringLiteral("session,time_s,frame,x_px,y_px")));
  EXPECT_EQ(lines[2].section(',', 0, 4), QStringLiteral("1,0.5,2,7,-4"));
}

TEST(TelemetryPlots, ANewSessionStartsTheGraphsAfreshAndTheCsvStaysMonotonicWithinEach) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  for (int i = 0; i < 5; ++i) client.publish(MakeTelemetry(i, i, 0, 360'000'000 + i * 100'000));
  plots.redraw();
  plots.startSession();  // the agent restarted: its clock is not the old one's
  for (int i = 0; i < 3; ++i) client.publish(MakeTelemetry(i, -i, 0, 1'000'000 + i * 100'000));
  client.publish(MakeTelemetry(3, -3, 0, 1'300'000));
  plots.redraw();
  QCPGraph* x = plots.graph(Curve::kDisplacementX);
  ASSERT_EQ(x->dataCount(), 4);
  EXPECT_DOUBLE_EQ(x->data()->at(0)->key, 0.0);
  EXPECT_NEAR(x->data()->at(3)->key, 0.3, 1e-9);

  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("t.csv"));
  ASSERT_TRUE(plots.exportCsv(path));
  QFile file(path);
  ASSERT_TRUE(file.open(QIODevice::ReadOnly));
  QStringList lines = QString::fromUtf8(file.readAll()).split('\n', Qt::SkipEmptyParts);
  lines.removeFirst();
  std::map<int, double> newest;  // session → time_s
  for (const QString& line : lines) {
    const int session = line.section(',', 0, 0).toInt();
    const double time_s = line.section(',', 1, 1).toDouble();
    if (newest.contains(session)) {
      EXPECT_GE(time_s, newest[session]) << line.toStdString();
    }
    newest[session] = time_s;
  }
  EXPECT_EQ(newest.size(), 2U);
}

TEST(TelemetryPlots, ACaptureClockGoingBackStartsANewSessionInsteadOfInterleaving) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  for (int i = 0; i < 5; ++i) client.publish(MakeTelemetry(i, 1, 0, 363'000'000 + i * 100'000));
  plots.redraw();
  client.publish(MakeTelemetry(5, 2, 0, 1'000'000));  // the simulated camera's clock again at 1 s
  client.publish(MakeTelemetry(6, 3, 0, 1'100'000));
  plots.redraw();
  EXPECT_EQ(plots.series().session(), 2);
  EXPECT_EQ(plots.series().clockRestarts(), 1U);
  QCPGraph* x = plots.graph(Curve::kDisplacementX);
  ASSERT_EQ(x->dataCount(), 2);
  EXPECT_DOUBLE_EQ(x->data()->at(0)->key, 0.0);
  EXPECT_NEAR(x->data()->at(1)->key, 0.1, 1e-9);
  EXPECT_TRUE(plots.stateText().contains(QStringLiteral("session 2")));
}

TEST(TelemetryPlots, PngExportWritesAnImage) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  plots.resize(600, 400);
  client.publish(MakeTelemetry(1, 5, -2, 1'000'000));
  plots.redraw();
  const QTemporaryDir dir;
  const QString path = dir.filePath(QStringLiteral("t.png"));
  ASSERT_TRUE(plots.exportPng(path));
  EXPECT_FALSE(QImage(path).isNull());
}

TEST(TelemetryPlots, AClickOnAGraphKeepsFollowing) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  plots.resize(600, 400);
  plots.show();
  ASSERT_TRUE(plots.followAction()->isChecked());
  QTest::mouseClick(plots.plot(), Qt::LeftButton, {}, QPoint(300, 100));
  EXPECT_TRUE(plots.followAction()->isChecked());
  EXPECT_TRUE(plots.stateText().startsWith(QStringLiteral("LIVE")));
}

TEST(TelemetryPlots, DraggingStopsFollowingAndSaysSo) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  plots.resize(600, 400);
  plots.show();
  QTest::mousePress(plots.plot(), Qt::LeftButton, {}, QPoint(300, 100));
  QMouseEvent move(QEvent::MouseMove, QPointF(340, 110),
                   plots.plot()->mapToGlobal(QPointF(340, 110)), Qt::NoButton, Qt::LeftButton,
                   Qt::NoModifier);
  QApplication::sendEvent(plots.plot(), &move);
  QTest::mouseRelease(plots.plot(), Qt::LeftButton, {}, QPoint(340, 110));
  EXPECT_FALSE(plots.followAction()->isChecked());
  EXPECT_TRUE(plots.stateText().startsWith(QStringLiteral("NOT FOLLOWING")));
}

TEST(TelemetryPlots, PauseIsWrittenAboveTheGraphs) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  plots.pauseAction()->setChecked(true);
  EXPECT_TRUE(plots.stateText().startsWith(QStringLiteral("PAUSED")));
  plots.pauseAction()->setChecked(false);
  EXPECT_TRUE(plots.stateText().startsWith(QStringLiteral("LIVE")));
}

TEST(TelemetryPlots, ResidualScaleIsTenPixelsGrowsForASpikeAndShrinksBack) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  std::int64_t t_us = 1'000'000;
  int frame = 0;
  const auto feed = [&](double seconds, int x_px) {
    for (; seconds > 0; seconds -= 0.1, t_us += 100'000) {
      client.publish(MakeTelemetry(++frame, x_px, 0, t_us));
    }
    plots.redraw();
  };
  feed(2, 3);
  EXPECT_DOUBLE_EQ(plots.residualRange().upper, TelemetryPlots::kResidualScalePx);
  EXPECT_DOUBLE_EQ(plots.residualRange().lower, -TelemetryPlots::kResidualScalePx);
  feed(0.1, 60);  // one spike
  EXPECT_GE(plots.residualRange().upper, 60);
  EXPECT_LE(plots.residualRange().lower, -60);
  feed(TelemetryPlots::kFollowWindowS + 1, 3);  // the spike has left the view
  EXPECT_DOUBLE_EQ(plots.residualRange().upper, TelemetryPlots::kResidualScalePx);
}

TEST(TelemetryPlots, DistanceHasAPlotOfItsOwn) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  EXPECT_NE(plots.graph(Curve::kDistance)->valueAxis()->axisRect(),
            plots.graph(Curve::kConfidence)->valueAxis()->axisRect());
  // And no legend sits inside a plot, over the newest data.
  for (int i = 0; i < plots.plot()->axisRectCount(); ++i) {
    EXPECT_EQ(plots.plot()->axisRect(i)->insetLayout()->elementCount(), 0);
  }
}

}  // namespace
}  // namespace kapfix::station
