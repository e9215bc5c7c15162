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
#include "groundstation/photos/photo_quality_table.hpp"
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
void PublishPhoto(FakeAgentClient& client, const std::string& name, std::size_t chunk_bytes,
                  const kapfix::v1::PhotoMetadata& quality = {}) {
  const std::string bytes = PngBytes();
  for (std::size_t offset = 0; offset < bytes.size(); offset += chunk_bytes) {
    kapfix::v1::Photo chunk;
    *chunk.mutable_metadata() = quality;
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

// Quality as an issue-13 agent measures it.
kapfix::v1::PhotoMetadata Quality(float blur_px, float offset_px, bool lock_lost = false) {
  kapfix::v1::PhotoMetadata m;
  m.set_view_blur_px(blur_px);
  m.set_residual_offset_px(offset_px);
  m.set_view_speed_px_per_frame(blur_px / 2);
  m.set_lock_lost(lock_lost);
  m.set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  m.set_shutter_wait_s(0.4F);
  m.set_shutter_reason("quietest predicted moment");
  m.set_sharpness_patch(812);
  m.set_sharpness_frame(455);
  m.set_exposure_ms(8);
  m.set_confidence(0.93F);
  m.set_camera(kapfix::v1::PHOTO_CAMERA_AGENT);
  m.set_camera_fallback_reason("gphoto2: no camera found");
  return m;
}

TEST(PhotosPanel, EachPhotosQualityIsListed) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "photo-0003.png", 1000, Quality(0.3F, 2.5F));
  const PhotoQualityTable& table = panel.quality();
  ASSERT_EQ(table.rowCount(), 1);
  const int row = table.rowOf(QStringLiteral("photo-0003.png"));
  ASSERT_EQ(row, 0);
  auto cell = [&](int column) { return table.item(row, column)->text(); };
  EXPECT_EQ(cell(PhotoQualityTable::kOffset), QStringLiteral("2.5"));
  EXPECT_EQ(cell(PhotoQualityTable::kBlur), QStringLiteral("0.3"));
  EXPECT_EQ(cell(PhotoQualityTable::kSpeed), QStringLiteral("0.15"));
  EXPECT_EQ(cell(PhotoQualityTable::kSharpnessPatch), QStringLiteral("812"));
  EXPECT_EQ(cell(PhotoQualityTable::kSharpnessFrame), QStringLiteral("455"));
  EXPECT_EQ(cell(PhotoQualityTable::kLock), QStringLiteral("trusted"));
  EXPECT_EQ(cell(PhotoQualityTable::kShutter), QStringLiteral("best-phase"));
  EXPECT_EQ(table.item(row, PhotoQualityTable::kShutter)->toolTip(),
            QStringLiteral("quietest predicted moment"));
  EXPECT_EQ(cell(PhotoQualityTable::kWait), QStringLiteral("0.4"));
  EXPECT_TRUE(
      cell(PhotoQualityTable::kCamera).contains(QStringLiteral("gphoto2: no camera found")));
  EXPECT_FALSE(table.flagged(row));
}

TEST(PhotosPanel, BlurredAndOffTargetPhotosAreFlagged) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "sharp.png", 1000, Quality(0.5F, 3));
  PublishPhoto(client, "blurred.png", 1000, Quality(2.4F, 3));
  PublishPhoto(client, "off.png", 1000, Quality(0.5F, 14));
  PublishPhoto(client, "lost.png", 1000, Quality(0.5F, 3, /*lock_lost=*/true));
  const PhotoQualityTable& table = panel.quality();
  EXPECT_FALSE(table.flagged(table.rowOf(QStringLiteral("sharp.png"))));
  EXPECT_TRUE(table.flagsOf(table.rowOf(QStringLiteral("blurred.png")))
                  .startsWith(QStringLiteral("BLURRED (2.4 px")));
  EXPECT_TRUE(table.flagsOf(table.rowOf(QStringLiteral("off.png")))
                  .startsWith(QStringLiteral("OFF TARGET (14.0 px")));
  EXPECT_EQ(table.flagsOf(table.rowOf(QStringLiteral("lost.png"))),
            QStringLiteral("OFF TARGET (lock lost)"));
}

TEST(PhotosPanel, PhotosSortByBlurAsNumbers) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "a.png", 1000, Quality(10.5F, 1));
  PublishPhoto(client, "b.png", 1000, Quality(2.0F, 1));
  PublishPhoto(client, "c.png", 1000, Quality(0.25F, 1));
  PhotoQualityTable& table = panel.quality();
  table.sortItems(PhotoQualityTable::kBlur, Qt::AscendingOrder);
  // As text "10.5" would come before "2".
  EXPECT_EQ(table.item(0, PhotoQualityTable::kName)->text(), QStringLiteral("c.png"));
  EXPECT_EQ(table.item(1, PhotoQualityTable::kName)->text(), QStringLiteral("b.png"));
  EXPECT_EQ(table.item(2, PhotoQualityTable::kName)->text(), QStringLiteral("a.png"));
}

TEST(PhotosPanel, ThePhotoFromAnOlderAgentShowsNoQualityAndNoFlag) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "old.png", 1000);
  const PhotoQualityTable& table = panel.quality();
  ASSERT_EQ(table.rowCount(), 1);
  EXPECT_EQ(table.item(0, PhotoQualityTable::kBlur)->text(), QStringLiteral("—"));
  EXPECT_FALSE(table.flagged(0));
}

TEST(PhotosPanel, TheSavedSidecarCarriesTheQualityFields) {
  const QTemporaryDir dir;
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.setFolder(dir.path());
  PublishPhoto(client, "photo-0009.png", 1000, Quality(0.5F, 3));
  QFile sidecar(dir.filePath(QStringLiteral("photo-0009.png.json")));
  ASSERT_TRUE(sidecar.open(QIODevice::ReadOnly));
  const QJsonObject m = QJsonDocument::fromJson(sidecar.readAll()).object();
  EXPECT_DOUBLE_EQ(m.value(QStringLiteral("view_blur_px")).toDouble(), 0.5);
  EXPECT_DOUBLE_EQ(m.value(QStringLiteral("residual_offset_px")).toDouble(), 3.0);
  EXPECT_EQ(m.value(QStringLiteral("shutter")).toString(), QStringLiteral("SHUTTER_BEST_PHASE"));
  EXPECT_EQ(m.value(QStringLiteral("shutter_reason")).toString(),
            QStringLiteral("quietest predicted moment"));
  EXPECT_DOUBLE_EQ(m.value(QStringLiteral("sharpness_patch")).toDouble(), 812);
  // A false lock_lost is written, not left out (absent would read as "not measured").
  ASSERT_TRUE(m.contains(QStringLiteral("lock_lost")));
  EXPECT_FALSE(m.value(QStringLiteral("lock_lost")).toBool());
  EXPECT_EQ(m.value(QStringLiteral("camera_fallback_reason")).toString(),
            QStringLiteral("gphoto2: no camera found"));
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
  EXPECT_EQ(panel.quality().rowCount(), 2);
}

TEST(PhotosPanel, IntervalSwitchSendsThePhotoInterval) {
  FakeAgentClient client;
  PhotosPanel panel(client);
  panel.intervalSeconds().setValue(5);
  panel.intervalSwitch().click();
  const auto* command = client.lastCommand(kapfix::v1::Command::kSetPhoto);
  ASSERT_NE(command, nullptr);
  EXPECT_FLOAT_EQ(command->set_photo().interval_s(), 5.0F);
  EXPECT_FALSE(command->set_photo().has_shutter()) << "only the interval changes";
  panel.intervalSwitch().click();
  EXPECT_FLOAT_EQ(client.lastCommand(kapfix::v1::Command::kSetPhoto)->set_photo().interval_s(),
                  0.0F);
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
