#include "groundstation/settings/setting_row.hpp"

#include <gtest/gtest.h>

#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTest>

namespace kapfix::station {
namespace {

// The camera gain as the schema has it: [0, 48] dB.
SettingRow::Spec Gain() {
  SettingRow::Spec spec;
  spec.key = QStringLiteral("gain");
  spec.label = QStringLiteral("Gain [dB]");
  spec.kind = SettingRow::Kind::kReal;
  spec.minimum = 0;
  spec.maximum = 48;
  spec.decimals = 1;
  spec.step = 0.1;
  spec.unit = QStringLiteral("dB");
  spec.help = QStringLiteral("camera analogue gain");
  return spec;
}

// Types `text` into the spin box as an operator would, and Enter.
void Type(QAbstractSpinBox& box, const QString& text) {
  box.selectAll();
  QTest::keyClicks(&box, text);
  QTest::keyClick(&box, Qt::Key_Return);
}

TEST(SettingRow, ShowsItsLimitsUnderTheEditorAndItsHelpAsTooltip) {
  SettingRow row(Gain(), QStringLiteral("camera analogue gain, [0, 48] dB"));
  EXPECT_EQ(row.hintLabel()->text(), QStringLiteral("0 to 48 dB"));
  EXPECT_FALSE(row.hintLabel()->isHidden());
  EXPECT_EQ(row.editor()->toolTip(), QStringLiteral("camera analogue gain, [0, 48] dB"));
}

TEST(SettingRow, ATypedMinusOneIsRefusedVisiblyAndKeptAsTyped) {
  SettingRow row(Gain(), {});
  QSignalSpy edited(&row, &SettingRow::edited);
  auto* box = qobject_cast<QDoubleSpinBox*>(row.editor());
  ASSERT_NE(box, nullptr);
  Type(*box, QStringLiteral("-1"));
  EXPECT_DOUBLE_EQ(box->value(), -1.0) << "not reverted";
  EXPECT_EQ(edited.count(), 0) << "not sent";
  EXPECT_TRUE(row.refusedLocally());
  EXPECT_TRUE(box->styleSheet().contains(QStringLiteral("border")));
  const QString message = row.statusLabel()->text();
  EXPECT_NE(message, QStringLiteral("✓"));
  EXPECT_TRUE(message.contains(QStringLiteral("camera analogue gain"))) << message.toStdString();
  EXPECT_TRUE(message.contains(QStringLiteral("0 to 48 dB"))) << message.toStdString();
}

TEST(SettingRow, A9999IsNotClampedButRefused) {
  SettingRow::Spec spec = Gain();
  spec.kind = SettingRow::Kind::kInteger;
  spec.maximum = 99;
  SettingRow row(spec, {});
  QSignalSpy edited(&row, &SettingRow::edited);
  auto* box = qobject_cast<QSpinBox*>(row.editor());
  ASSERT_NE(box, nullptr);
  Type(*box, QStringLiteral("9999"));
  EXPECT_EQ(box->value(), 9999);
  EXPECT_EQ(edited.count(), 0);
  EXPECT_TRUE(row.statusLabel()->text().startsWith(QStringLiteral("9999 is not possible")))
      << row.statusLabel()->text().toStdString();
}

TEST(SettingRow, TheMessageGoesWhenTheValueIsFixed) {
  SettingRow row(Gain(), {});
  QSignalSpy edited(&row, &SettingRow::edited);
  auto* box = qobject_cast<QDoubleSpinBox*>(row.editor());
  ASSERT_NE(box, nullptr);
  Type(*box, QStringLiteral("99"));
  ASSERT_TRUE(row.refusedLocally());
  Type(*box, QStringLiteral("12"));
  EXPECT_FALSE(row.refusedLocally());
  EXPECT_TRUE(row.statusLabel()->text().isEmpty()) << row.statusLabel()->text().toStdString();
  EXPECT_TRUE(box->styleSheet().isEmpty());
  ASSERT_EQ(edited.count(), 1);
  EXPECT_EQ(edited.front().at(1).toString(), QStringLiteral("12"));
}

TEST(SettingRow, ZeroIsAcceptedWhereItMeansOff) {
  SettingRow::Spec spec = Gain();
  spec.minimum = 0.1;
  spec.maximum = 60;
  spec.zero_means_off = true;
  spec.decimals = 2;
  spec.unit = QStringLiteral("fps");
  SettingRow row(spec, {});
  QSignalSpy edited(&row, &SettingRow::edited);
  auto* box = qobject_cast<QDoubleSpinBox*>(row.editor());
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(row.hintLabel()->text(), QStringLiteral("0 (off) or 0.1 to 60 fps"));
  Type(*box, QStringLiteral("0.05"));
  EXPECT_TRUE(row.refusedLocally());
  Type(*box, QStringLiteral("0"));
  EXPECT_FALSE(row.refusedLocally());
  EXPECT_EQ(edited.count(), 1);
}

// A value the operator is fixing is not overwritten by the agent's state meanwhile.
TEST(SettingRow, TheAgentsValueDoesNotReplaceARefusedOne) {
  SettingRow row(Gain(), {});
  auto* box = qobject_cast<QDoubleSpinBox*>(row.editor());
  ASSERT_NE(box, nullptr);
  Type(*box, QStringLiteral("99"));
  row.showAgentValue(QStringLiteral("6"));
  EXPECT_DOUBLE_EQ(box->value(), 99.0);
  row.markPending();
  row.markRefused(QStringLiteral("camera busy"));
  row.showAgentValue(QStringLiteral("6"));
  EXPECT_DOUBLE_EQ(box->value(), 99.0);
}

}  // namespace
}  // namespace kapfix::station
