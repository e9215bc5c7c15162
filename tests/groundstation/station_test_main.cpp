// The station's tests run inside one QApplication on the offscreen platform (the test's
// ENVIRONMENT sets QT_QPA_PLATFORM), with QSettings redirected to a private folder so that
// no test reads or writes the operator's real settings.
#include <gtest/gtest.h>

#include <QApplication>
#include <QSettings>
#include <QTemporaryDir>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // Test discovery at build time runs this without the test's ENVIRONMENT: no display there.
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("kapfix-test"));
  QApplication::setApplicationName(QStringLiteral("kapfix-station-test"));
  const QTemporaryDir settings_dir;
  QSettings::setDefaultFormat(QSettings::IniFormat);
  QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, settings_dir.path());
  return RUN_ALL_TESTS();
}
