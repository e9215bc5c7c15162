#include "groundstation/video/video_panel.hpp"

#include <gtest/gtest.h>

#include <QSettings>
#include <QTest>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::MakeVideoFrame;
using testing::ProcessEvents;

TEST(VideoPanel, FrameFromTheAgentIsShown) {
  FakeAgentClient client;
  VideoPanel panel(client);
  client.publish(MakeVideoFrame(320, 240, 9));
  EXPECT_TRUE(panel.view().hasPicture());
  EXPECT_EQ(panel.view().frameNumber(), 7U);
}

TEST(VideoPanel, ClickingSliceThreeSendsSelectSliceThree) {
  FakeAgentClient client;
  VideoPanel panel(client);
  panel.resize(800, 700);
  panel.show();
  client.publish(MakeVideoFrame(300, 270, 9));
  const QPointF centre = panel.view().sliceCentre(3);
  ASSERT_FALSE(centre.isNull());
  QTest::mouseClick(&panel.view(), Qt::LeftButton, {}, centre.toPoint());
  const auto* command = client.lastCommand(kapfix::v1::Command::kSelectSlice);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->select_slice(), 3U);
  ProcessEvents();
  EXPECT_EQ(panel.messageText(), QStringLiteral("Slice 3 selected"));
}

TEST(VideoPanel, ClickOutsideThePictureSendsNothing) {
  FakeAgentClient client;
  VideoPanel panel(client);
  panel.resize(800, 300);  // wide: bars left and right of a square picture
  panel.show();
  client.publish(MakeVideoFrame(270, 270, 9));
  QTest::mouseClick(&panel.view(), Qt::LeftButton, {}, QPoint(2, 100));
  EXPECT_TRUE(client.commands().empty());
}

TEST(VideoPanel, OverlaySwitchIsRememberedBetweenRuns) {
  QSettings().clear();
  FakeAgentClient client;
  {
    VideoPanel panel(client);
    EXPECT_TRUE(panel.view().overlayOptions().slice_grid);
    panel.overlaySwitch(QStringLiteral("overlay_slice_grid"))->click();
    EXPECT_FALSE(panel.view().overlayOptions().slice_grid);
  }
  const VideoPanel again(client);
  EXPECT_FALSE(again.overlaySwitch(QStringLiteral("overlay_slice_grid"))->isChecked());
  QSettings().clear();
}

TEST(VideoPanel, EachOverlayCanBeSwitchedOff) {
  QSettings().clear();
  FakeAgentClient client;
  VideoPanel panel(client);
  for (const char* name : {"overlay_slice_grid", "overlay_chosen_slice", "overlay_reference_patch",
                           "overlay_current_match", "overlay_crosshair"}) {
    panel.overlaySwitch(QLatin1String(name))->click();
  }
  const OverlayOptions& options = panel.view().overlayOptions();
  EXPECT_FALSE(options.slice_grid || options.chosen_slice || options.reference_patch ||
               options.current_match || options.crosshair);
  QSettings().clear();
}

}  // namespace
}  // namespace kapfix::station
