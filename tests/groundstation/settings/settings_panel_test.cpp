#include "groundstation/settings/settings_panel.hpp"

#include <gtest/gtest.h>

#include <QComboBox>
#include <QDoubleSpinBox>

#include "groundstation/client/fake_agent_client.hpp"
#include "groundstation/settings/calibration_view.hpp"
#include "groundstation/settings/setting_row.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::ProcessEvents;

TEST(SettingsPanel, ChangingAGainSendsItToTheAgent) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  auto* p = qobject_cast<QDoubleSpinBox*>(panel.row(QStringLiteral("p"))->editor());
  ASSERT_NE(p, nullptr);
  p->setValue(1.25);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetGains);
  ASSERT_NE(command, nullptr);
  EXPECT_FLOAT_EQ(command->set_gains().p(), 1.25F);
  EXPECT_FALSE(command->set_gains().has_i()) << "only the changed field travels";
  ProcessEvents();
  EXPECT_EQ(panel.row(QStringLiteral("p"))->statusLabel()->text(), QStringLiteral("✓"));
}

// The editors take range, unit and help from the settings schema: the gain ranges the agent
// checks are the ones the operator can dial.
TEST(SettingsPanel, AnEditorHasTheSchemasRangeUnitAndHelp) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  SettingRow* rate = panel.row(QStringLiteral("rate_limit"));
  ASSERT_NE(rate, nullptr);
  auto* box = qobject_cast<QDoubleSpinBox*>(rate->editor());
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(rate->hintLabel()->text(), QStringLiteral("1 to 1000 deg/s"));
  EXPECT_TRUE(box->toolTip().contains(QStringLiteral("[1, 1000] deg/s")))
      << box->toolTip().toStdString();
  EXPECT_EQ(panel.row(QStringLiteral("i"))->hintLabel()->text(), QStringLiteral("0 to 10 1/s"));
  EXPECT_EQ(panel.row(QStringLiteral("video_fps"))->hintLabel()->text(),
            QStringLiteral("0 (off) or 0.1 to 60 fps"));
}

// The agent's reason names the field in the command; the operator reads what it is.
TEST(SettingsPanel, TheAgentsRefusalReadsInPlainWords) {
  FakeAgentClient client;
  client.refuse(kapfix::v1::Command::kSetCamera, "set_camera.gain_db = 47: must be in [0, 46] dB");
  SettingsPanel panel(client);
  SettingRow* gain = panel.row(QStringLiteral("gain"));
  auto* box = qobject_cast<QDoubleSpinBox*>(gain->editor());
  ASSERT_NE(box, nullptr);
  box->setValue(47);
  ProcessEvents();
  const QString shown = gain->statusLabel()->text();
  EXPECT_EQ(shown, QStringLiteral("camera analogue gain = 47: must be in [0, 46] dB"));
  EXPECT_FALSE(shown.contains(QStringLiteral("set_camera")));
  // Fixed, the message goes and the ✓ shows.
  client.accept(kapfix::v1::Command::kSetCamera);
  box->setValue(12);
  ProcessEvents();
  EXPECT_EQ(gain->statusLabel()->text(), QStringLiteral("✓"));
}

TEST(SettingsPanel, AValueOutOfTheSchemasRangeIsNotSent) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  auto* gain = qobject_cast<QDoubleSpinBox*>(panel.row(QStringLiteral("gain"))->editor());
  ASSERT_NE(gain, nullptr);
  gain->setValue(9999);
  EXPECT_EQ(client.lastCommand(kapfix::v1::Command::kSetCamera), nullptr);
  EXPECT_TRUE(panel.row(QStringLiteral("gain"))->refusedLocally());
}

// Issue 13: the shutter settings are edited like every other, through the schema.
TEST(SettingsPanel, TheShutterSettingsHaveTheirRowsAndChoosingBestPhaseSendsSetPhoto) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  for (const char* key :
       {"shutter", "shutter_window", "shutter_window_cap", "photo_exposure", "photo_camera"}) {
    EXPECT_NE(panel.row(QLatin1String(key)), nullptr) << key;
  }
  auto* shutter = qobject_cast<QComboBox*>(panel.row(QStringLiteral("shutter"))->editor());
  ASSERT_NE(shutter, nullptr);
  const int best = shutter->findText(QStringLiteral("best-phase"));
  ASSERT_GE(best, 0);
  shutter->setCurrentIndex(best);
  emit shutter->activated(best);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetPhoto);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_photo().shutter(), kapfix::v1::SHUTTER_BEST_PHASE);

  kapfix::v1::AgentState state;
  state.mutable_photo()->set_shutter(kapfix::v1::SHUTTER_INTERVAL);
  state.mutable_photo()->set_exposure_ms(8);
  ProcessEvents();
  client.publish(state);
  EXPECT_EQ(panel.row(QStringLiteral("shutter"))->value(), QStringLiteral("interval"));
  EXPECT_EQ(panel.row(QStringLiteral("photo_exposure"))->value(), QStringLiteral("8"));
}

TEST(SettingsPanel, RefusedSettingShowsTheAgentsReasonNextToItsControl) {
  FakeAgentClient client;
  client.refuse(kapfix::v1::Command::kSetSearch, "patch_size_px 990 does not fit the frame");
  SettingsPanel panel(client);
  auto* patch = qobject_cast<QSpinBox*>(panel.row(QStringLiteral("patch_size"))->editor());
  ASSERT_NE(patch, nullptr);
  patch->setValue(990);
  ProcessEvents();
  EXPECT_EQ(panel.row(QStringLiteral("patch_size"))->statusLabel()->text(),
            QStringLiteral("patch_size_px 990 does not fit the frame"));
  EXPECT_TRUE(panel.row(QStringLiteral("p"))->statusLabel()->text().isEmpty());
}

TEST(SettingsPanel, ChoosingAStrategySendsItsName) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  auto* strategy = qobject_cast<QComboBox*>(panel.row(QStringLiteral("strategy"))->editor());
  ASSERT_NE(strategy, nullptr);
  const int pyr = strategy->findText(QStringLiteral("pyr"));
  strategy->setCurrentIndex(pyr);
  emit strategy->activated(pyr);
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetSearch);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_search().strategy(), "pyr");
}

TEST(SettingsPanel, AgentStateFillsTheEditorsWithoutSendingAnything) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  kapfix::v1::AgentState state;
  state.mutable_gains()->set_p(0.6F);
  state.mutable_search()->set_strategy("h15");
  state.mutable_search()->set_axis(kapfix::v1::AXIS_Y);
  state.mutable_camera()->set_exposure_us(2500);
  client.publish(state);
  EXPECT_EQ(panel.row(QStringLiteral("p"))->value(), QStringLiteral("0.6"));
  EXPECT_EQ(panel.row(QStringLiteral("strategy"))->value(), QStringLiteral("h15"));
  EXPECT_EQ(panel.row(QStringLiteral("axis"))->value(), QStringLiteral("y"));
  EXPECT_EQ(panel.row(QStringLiteral("exposure"))->value(), QStringLiteral("2500"));
  EXPECT_TRUE(client.commands().empty());
}

TEST(SettingsPanel, EveryIssueSettingHasARow) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  for (const char* key : {"p", "i", "d", "dead_band", "rate_limit", "strategy", "sampling",
                          "patch_size", "slice_count", "axis", "gain", "exposure", "lens"}) {
    EXPECT_NE(panel.row(QLatin1String(key)), nullptr) << key;
  }
}

TEST(CalibrationView, RunStartsCalibrationAndTheResultShowsFitAndResidual) {
  FakeAgentClient client;
  SettingsPanel panel(client);
  panel.calibration().runButton().click();
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetMode);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->set_mode().mode(), kapfix::v1::MODE_CALIBRATE);
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile("3.5mm");
  report.set_finished(true);
  report.mutable_pan()->set_valid(true);
  report.mutable_pan()->set_units_per_px_fit(0.0512);
  report.mutable_pan()->set_units_per_px_median(0.05);
  report.mutable_pan()->set_residual_px(0.42);
  report.mutable_pan()->set_samples(105);
  client.publish(report);
  const QString text = panel.calibration().resultText();
  EXPECT_TRUE(text.contains(QStringLiteral("0.0512 deg/px"))) << text.toStdString();
  EXPECT_TRUE(text.contains(QStringLiteral("residual 0.42 px"))) << text.toStdString();
}

}  // namespace
}  // namespace kapfix::station
