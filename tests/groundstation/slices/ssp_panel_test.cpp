#include "groundstation/slices/ssp_panel.hpp"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include "groundstation/client/fake_agent_client.hpp"
#include "groundstation/slices/slice_graph_grid.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeSliceReport;
using testing::ProcessEvents;

TEST(SspPanel, RunSendsSspWithTheDeadline) {
  FakeAgentClient client;
  SspPanel panel(client);
  panel.runAction()->trigger();
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetMode);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_mode().mode(), kapfix::v1::MODE_SSP);
  EXPECT_GT(command->set_mode().deadline_frames(), 0U);
}

TEST(SspPanel, ProgressFollowsTheReports) {
  FakeAgentClient client;
  SspPanel panel(client);
  kapfix::v1::SliceReport progress;
  progress.set_progress_done(120);
  progress.set_progress_total(400);
  client.publish(progress);
  EXPECT_EQ(panel.progress().value(), 120);
  EXPECT_EQ(panel.progress().maximum(), 400);
}

TEST(SspPanel, ReportFillsTheTableAndHighlightsTheRecommendedSlice) {
  FakeAgentClient client;
  SspPanel panel(client);
  client.publish(MakeSliceReport(9, 3));
  ASSERT_EQ(panel.table().rowCount(), 9);
  EXPECT_EQ(panel.table().item(2, SspPanel::kDc)->text(), QStringLiteral("21"));
  EXPECT_EQ(panel.table().item(4, SspPanel::kFft)->text(), QStringLiteral("5.00"));
  EXPECT_TRUE(panel.table().item(2, SspPanel::kDc)->font().bold());
  EXPECT_FALSE(panel.table().item(3, SspPanel::kDc)->font().bold());
  EXPECT_EQ(panel.recommended(), 3U);
  EXPECT_TRUE(panel.confirmAction()->isEnabled());
}

TEST(SspPanel, EverySliceGetsItsOwnGraph) {
  FakeAgentClient client;
  SspPanel panel(client);
  client.publish(MakeSliceReport(9, 3));
  for (unsigned i = 1; i <= 9; ++i) {
    ASSERT_NE(panel.graphs().plotOf(i), nullptr);
    EXPECT_EQ(panel.graphs().plotOf(i)->graph(0)->dataCount(), 40);
  }
  EXPECT_EQ(panel.graphs().plotOf(10), nullptr);
  EXPECT_EQ(panel.graphs().highlighted(), 3U);
}

TEST(SspPanel, ConfirmSendsTheRecommendedSlice) {
  FakeAgentClient client;
  SspPanel panel(client);
  client.publish(MakeSliceReport(9, 3));
  panel.confirmAction()->trigger();
  const auto* command = client.lastCommand(kapfix::v1::Command::kSelectSlice);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->select_slice(), 3U);
  ProcessEvents();
  EXPECT_EQ(panel.messageText(), QStringLiteral("Fixating on slice 3"));
}

TEST(SspPanel, DoubleClickingARowPicksThatSlice) {
  FakeAgentClient client;
  SspPanel panel(client);
  client.publish(MakeSliceReport(9, 3));
  emit panel.table().cellDoubleClicked(6, SspPanel::kDc);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSelectSlice);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->select_slice(), 7U);
}

TEST(SspPanel, RefusedPickShowsTheAgentsReason) {
  FakeAgentClient client;
  client.refuse(kapfix::v1::Command::kSelectSlice, "not possible in mode idle");
  SspPanel panel(client);
  panel.pickSlice(5);
  ProcessEvents();
  EXPECT_TRUE(panel.messageText().contains(QStringLiteral("not possible in mode idle")));
}

}  // namespace
}  // namespace kapfix::station
