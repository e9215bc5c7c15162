#include "groundstation/plots/telemetry_plots.hpp"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QFile>
#include <QTemporaryDir>

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
  EXPECT_TRUE(lines[0].startsWith(QStringLiteral("time_s,frame,x_px,y_px")));
  EXPECT_EQ(lines[2].section(',', 0, 3), QStringLiteral("0.5,2,7,-4"));
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

TEST(TelemetryPlots, ZoomingStopsFollowingTheNewestData) {
  FakeAgentClient client;
  TelemetryPlots plots(client);
  plots.resize(600, 400);
  plots.show();
  ASSERT_TRUE(plots.followAction()->isChecked());
  QTest::mousePress(plots.plot(), Qt::LeftButton, {}, QPoint(300, 100));
  QTest::mouseRelease(plots.plot(), Qt::LeftButton, {}, QPoint(300, 100));
  EXPECT_FALSE(plots.followAction()->isChecked());
}

}  // namespace
}  // namespace kapfix::station
