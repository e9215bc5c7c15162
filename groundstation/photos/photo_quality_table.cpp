#include "groundstation/photos/photo_quality_table.hpp"

#include <QHeaderView>
#include <cmath>

#include "groundstation/photos/photo_quality.hpp"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::station {
namespace {

const QColor kFlaggedBackground(255, 222, 219);

// A number cell: the value itself is the data, so that the column sorts by it.
QTableWidgetItem* Number(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  auto* item = new QTableWidgetItem;
  item->setData(Qt::DisplayRole, std::round(value * scale) / scale);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  return item;
}

QTableWidgetItem* Text(const QString& text, const QString& tooltip = {}) {
  auto* item = new QTableWidgetItem(text);
  if (!tooltip.isEmpty()) item->setToolTip(tooltip);
  return item;
}

QString Word(const google::protobuf::EnumValueDescriptor* value) {
  return value == nullptr ? QString() : QString::fromStdString(kapfix::v1::SettingWord(*value));
}

}  // namespace

PhotoQualityTable::PhotoQualityTable(QWidget* parent) : QTableWidget(0, kColumns, parent) {
  setObjectName(QStringLiteral("photoQuality"));
  setHorizontalHeaderLabels({tr("Photo"), tr("Offset [px]"), tr("Speed [px/frame]"),
                             tr("Blur [px]"), tr("Sharpness patch"), tr("Sharpness frame"),
                             tr("Confidence"), tr("Lock"), tr("Shutter"), tr("Wait [s]"),
                             tr("Camera"), tr("Flags")});
  const QStringList tips = {
      tr("File name on the agent and in the photo folder"),
      tr("Distance of the view from the reference at capture; off target above %1 px")
          .arg(kOffTargetPx),
      tr("Residual view speed at capture"),
      tr("View travel during the exposure; blurred above %1 px").arg(kBlurredPx),
      tr("Variance of the Laplacian on the reference patch's region [grey²]: higher is sharper"),
      tr("Variance of the Laplacian over the whole photo [grey²]: higher is sharper"),
      tr("Match confidence at capture [0..1]"),
      tr("Whether the match was trusted at capture"),
      tr("Shutter mode that fired (reason as tooltip)"),
      tr("From the request to the capture"),
      tr("Camera that took it (why another one did, as tooltip)"),
      tr("Blurred or off target")};
  for (int column = 0; column < kColumns; ++column) {
    horizontalHeaderItem(column)->setToolTip(tips.at(column));
  }
  setEditTriggers(QAbstractItemView::NoEditTriggers);
  setSelectionBehavior(QAbstractItemView::SelectRows);
  setSortingEnabled(true);
  verticalHeader()->setVisible(false);
  horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  horizontalHeader()->setStretchLastSection(true);
}

int PhotoQualityTable::rowOf(const QString& file_name) const {
  for (int row = 0; row < rowCount(); ++row) {
    if (item(row, kName) != nullptr && item(row, kName)->text() == file_name) return row;
  }
  return -1;
}

QString PhotoQualityTable::flagsOf(int row) const {
  const QTableWidgetItem* cell = item(row, kFlags);
  return cell == nullptr ? QString() : cell->text();
}

void PhotoQualityTable::addPhoto(const SavedPhoto& photo) {
  const kapfix::v1::PhotoMetadata& m = photo.metadata;
  const QString name = QString::fromStdString(m.file_name());
  if (rowOf(name) >= 0) return;
  const PhotoJudgement judgement = JudgePhoto(m);
  // Sorting moves rows while they are filled: off until the row is complete.
  setSortingEnabled(false);
  const int row = rowCount();
  insertRow(row);
  auto* name_item = Text(name, photo.image_path);
  name_item->setData(Qt::UserRole, photo.image_path);
  setItem(row, kName, name_item);
  setItem(row, kConfidence, Number(m.confidence(), 2));
  if (judgement.measured) {
    setItem(row, kOffset, Number(m.residual_offset_px(), 1));
    setItem(row, kSpeed, Number(m.view_speed_px_per_frame(), 2));
    setItem(row, kBlur, Number(m.view_blur_px(), 2));
    setItem(row, kSharpnessPatch, Number(m.sharpness_patch(), 0));
    setItem(row, kSharpnessFrame, Number(m.sharpness_frame(), 0));
    setItem(row, kLock, Text(m.lock_lost() ? tr("lost") : tr("trusted")));
    setItem(row, kShutter,
            Text(Word(kapfix::v1::Shutter_descriptor()->FindValueByNumber(m.shutter())),
                 QString::fromStdString(m.shutter_reason())));
    setItem(row, kWait, Number(m.shutter_wait_s(), 2));
    QString camera = Word(kapfix::v1::PhotoCamera_descriptor()->FindValueByNumber(m.camera()));
    const QString fallback = QString::fromStdString(m.camera_fallback_reason());
    if (!fallback.isEmpty()) camera += tr(" (instead: %1)").arg(fallback);
    setItem(row, kCamera, Text(camera, fallback));
  } else {
    for (int column : {kOffset, kSpeed, kBlur, kSharpnessPatch, kSharpnessFrame, kLock, kShutter,
                       kWait, kCamera}) {
      setItem(row, column, Text(QStringLiteral("—"), tr("Not measured by this agent")));
    }
  }
  setItem(row, kFlags, Text(QString::fromStdString(judgement.flags)));
  if (!judgement.flags.empty()) {
    for (int column = 0; column < kColumns; ++column) {
      item(row, column)->setBackground(kFlaggedBackground);
    }
    item(row, kFlags)->setForeground(QColor(0xb3, 0x26, 0x1e));
  }
  setSortingEnabled(true);
}

}  // namespace kapfix::station
