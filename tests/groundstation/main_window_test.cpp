#include "groundstation/main_window.hpp"

#include <gtest/gtest.h>

#include <QSettings>
#include <QTest>

#include "groundstation/client/fake_agent_client.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

TEST(MainWindow, SpaceInTheWindowTakesAPhoto) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  window.show();
  window.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
  QTest::keyClick(&window, Qt::Key_Space);
  EXPECT_NE(client.lastCommand(kapfix::v1::Command::kTakePhoto), nullptr);
}

TEST(MainWindow, F5StartsSsp) {
  FakeAgentClient client;
  MainWindow window({&client, nullptr, nullptr});
  window.show();
  window.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
  QTest::keyClick(&window, Qt::Key_F5);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetMode);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_mode().mode(), kapfix::v1::MODE_SSP);
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
