#include "groundstation/photos/photos_panel.hpp"

#include <gtest/gtest.h>

#include <QBuffer>
#include <QFile>
#include <QImage>
#include <QJsonDocument>
#include <QJsonObject>
#include <QMainWindow>
#include <QTemporaryDir>
#include <QTest>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

using testing::ProcessEvents;

std::string PngBytes() {
  QImage image(64, 48, QImage::Format_RGB32);
  image.fill(Qt::darkCyan);
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  image.save(&buffer, "PNG");
  return bytes.toStdString();
}

// A photo as the agent sends it: in chunks, metadata repeated in each.
void PublishPhoto(FakeAgentClient& client, const std::string& name, std::size_t chunk_bytes) {
  const std::string bytes = PngBytes();
  for (std::size_t offset = 0; offset < bytes.size(); offset += chunk_bytes) {
    kapfix::v1::Photo chunk;
    chunk.mutable_metadata()->set_file_name(name);
    chunk.mutable_metadata()->set_format("png");
    chunk.mutable_metadata()->set_slice(4);
    chunk.mutable_metadata()->set_capture_time_us(123'456);
    chunk.set_offset_bytes(offset);
    chunk.set_total_bytes(bytes.size());
    chunk.set_data(bytes.substr(offset, chunk_bytes));
    client.publish(chunk);
  }
}

TEST(PhotosPanel, SpaceTriggersTakePhoto) {
  FakeAgentClient client;
  QMainWindow window;
  auto* panel = new PhotosPanel(client);
  window.setCentralWidget(panel);
  window.addAction(panel->captureAction());
  window.show();
  window.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&window));
  QTest::keyClick(&window, Qt::Key_Space);
  EXPECT_NE(client.lastCommand(kapfix::v1::Command::kTakePhoto), nullptr);
}

TEST(PhotosPanel, ReceivedPhotoIsSavedWithItsSidecarAndShownInTheGallery) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "photo-0007.png", 100);
  const QString image = dir.filePath(QStringLiteral("photo-0007.png"));
  EXPECT_FALSE(QImage(image).isNull());
  QFile sidecar(image + QStringLiteral(".json"));
  ASSERT_TRUE(sidecar.open(QIODevice::ReadOnly));
  const QJsonObject metadata = QJsonDocument::fromJson(sidecar.readAll()).object();
  EXPECT_EQ(metadata.value(QStringLiteral("slice")).toInt(), 4);
  EXPECT_EQ(metadata.value(QStringLiteral("file_name")).toString(),
            QStringLiteral("photo-0007.png"));
  ASSERT_EQ(panel.gallery().count(), 1);
  EXPECT_FALSE(panel.gallery().item(0)->icon().isNull());
}

TEST(PhotosPanel, PhotoResentAfterALinkLossIsNotShownTwice) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "photo-0001.png", 1000);
  PublishPhoto(client, "photo-0001.png", 1000);
  PublishPhoto(client, "photo-0002.png", 1000);
  EXPECT_EQ(panel.gallery().count(), 2);
}

TEST(PhotosPanel, IntervalSwitchSendsThePhotoInterval) {
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.intervalSeconds().setValue(5);
  panel.intervalSwitch().click();
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetPhotoIntervalS);
  ASSERT_NE(command, nullptr);
  EXPECT_FLOAT_EQ(command->set_photo_interval_s(), 5.0F);
  panel.intervalSwitch().click();
  EXPECT_FLOAT_EQ(
      client.lastCommand(kapfix::v1::Command::kSetPhotoIntervalS)->set_photo_interval_s(), 0.0F);
}

TEST(PhotosPanel, FolderIsRememberedBetweenRuns) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  {
    PhotosPanel panel(client);
    panel.setFolder(dir.path());
  }
  const PhotosPanel again(client);
  EXPECT_EQ(again.folder(), dir.path());
}

TEST(PhotosPanel, RefusedCaptureShowsTheReason) {
  FakeAgentClient client;
  client.refuse(kapfix::v1::Command::kTakePhoto, "disk full");
  PhotosPanel panel(client);
  panel.captureAction()->trigger();
  ProcessEvents();
  EXPECT_TRUE(panel.messageText().contains(QStringLiteral("disk full")));
}

}  // namespace
}  // namespace kapfix::station
