#include "groundstation/photos/photos_panel.hpp"

#include <QDesktopServices>
#include <QDir>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QImage>
#include <QPointer>
#include <QSettings>
#include <QStandardPaths>
#include <QToolButton>
#include <QUrl>
#include <QVBoxLayout>
#include <stdexcept>

#include "groundstation/photos/photo_quality.hpp"
#include "groundstation/photos/photo_quality_table.hpp"

namespace kapfix::station {
namespace {

QString DefaultFolder() {
  return QDir(QStandardPaths::writableLocation(QStandardPaths::PicturesLocation))
      .filePath(QStringLiteral("kapfix"));
}

}  // namespace

PhotosPanel::PhotosPanel(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      client_(client),
      capture_(new QAction(tr("Capture now"), this)),
      interval_on_(new QCheckBox(tr("Every"), this)),
      interval_s_(new QDoubleSpinBox(this)),
      folder_edit_(new QLineEdit(this)),
      gallery_(new QListWidget(this)),
      quality_(new PhotoQualityTable(this)),
      message_(new QLabel(this)) {
  capture_->setShortcut(QKeySequence(Qt::Key_Space));
  capture_->setToolTip(tr("Save a stabilised photo on the agent and fetch it (Space)"));

  const QSettings settings;
  interval_s_->setRange(0.5, 3600);
  interval_s_->setDecimals(1);
  interval_s_->setSuffix(tr(" s"));
  interval_s_->setValue(settings.value(QStringLiteral("photos/interval_s"), 10.0).toDouble());
  interval_s_->setKeyboardTracking(false);
  interval_on_->setToolTip(tr("The agent saves a photo every N seconds, link or no link"));
  setFolder(settings.value(QStringLiteral("photos/folder"), DefaultFolder()).toString());
  folder_edit_->setReadOnly(true);

  auto* capture_button = new QToolButton(this);
  capture_button->setDefaultAction(capture_);
  capture_button->setToolButtonStyle(Qt::ToolButtonTextOnly);
  capture_button->setMinimumHeight(40);
  auto* choose = new QToolButton(this);
  choose->setText(tr("Folder…"));
  auto* open = new QToolButton(this);
  open->setText(tr("Open"));

  auto* top = new QHBoxLayout;
  top->addWidget(capture_button);
  top->addSpacing(12);
  top->addWidget(interval_on_);
  top->addWidget(interval_s_);
  top->addStretch(1);
  auto* folder_row = new QHBoxLayout;
  folder_row->addWidget(folder_edit_, 1);
  folder_row->addWidget(choose);
  folder_row->addWidget(open);

  gallery_->setObjectName(QStringLiteral("photoGallery"));
  gallery_->setViewMode(QListView::IconMode);
  gallery_->setFlow(QListView::LeftToRight);
  gallery_->setWrapping(false);
  gallery_->setIconSize(QSize(kThumbnailPx * 4 / 3, kThumbnailPx));
  gallery_->setMinimumHeight(kThumbnailPx + 48);
  gallery_->setMovement(QListView::Static);
  message_->setWordWrap(true);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top);
  layout->addLayout(folder_row);
  layout->addWidget(gallery_);
  quality_->setMinimumHeight(160);
  layout->addWidget(quality_, 1);
  layout->addWidget(message_);

  connect(capture_, &QAction::triggered, this, &PhotosPanel::capture);
  connect(interval_on_, &QCheckBox::clicked, this, &PhotosPanel::sendInterval);
  connect(interval_s_, &QDoubleSpinBox::valueChanged, this, [this](double seconds) {
    QSettings().setValue(QStringLiteral("photos/interval_s"), seconds);
    if (interval_on_->isChecked()) sendInterval();
  });
  connect(choose, &QToolButton::clicked, this, &PhotosPanel::chooseFolder);
  connect(open, &QToolButton::clicked, this,
          [this] { QDesktopServices::openUrl(QUrl::fromLocalFile(store_.folder())); });
  connect(gallery_, &QListWidget::itemActivated, this, [](QListWidgetItem* item) {
    QDesktopServices::openUrl(QUrl::fromLocalFile(item->data(Qt::UserRole).toString()));
  });
  connect(quality_, &QTableWidget::itemActivated, this, [this](QTableWidgetItem* item) {
    const QTableWidgetItem* name = quality_->item(item->row(), PhotoQualityTable::kName);
    if (name != nullptr) {
      QDesktopServices::openUrl(QUrl::fromLocalFile(name->data(Qt::UserRole).toString()));
    }
  });
  connect(&client_, &AgentClient::photoChunkReceived, this, &PhotosPanel::receive);
  connect(&client_, &AgentClient::stateReceived, this, [this](const kapfix::v1::AgentState& state) {
    const float interval_s = state.photo().interval_s();
    interval_on_->setChecked(interval_s > 0);
    if (interval_s > 0) {
      const QSignalBlocker blocker(interval_s_);
      interval_s_->setValue(interval_s);
    }
  });
}

void PhotosPanel::setFolder(const QString& folder) {
  store_.setFolder(folder);
  folder_edit_->setText(folder);
  QSettings().setValue(QStringLiteral("photos/folder"), folder);
}

void PhotosPanel::chooseFolder() {
  const QString folder =
      QFileDialog::getExistingDirectory(this, tr("Folder for the photos"), store_.folder());
  if (!folder.isEmpty()) setFolder(folder);
}

void PhotosPanel::capture() {
  kapfix::v1::Command command;
  command.mutable_take_photo();
  message_->setText(tr("Capturing …"));
  client_.sendCommand(std::move(command), [self = QPointer(this)](const CommandOutcome& outcome) {
    if (self.isNull()) return;
    self->message_->setText(outcome.ok ? tr("Photo taken; receiving …")
                                       : tr("Photo refused: %1").arg(outcome.reason));
  });
}

void PhotosPanel::sendInterval() {
  kapfix::v1::Command command;
  const double seconds = interval_on_->isChecked() ? interval_s_->value() : 0.0;
  command.mutable_set_photo()->set_interval_s(static_cast<float>(seconds));
  client_.sendCommand(
      std::move(command), [self = QPointer(this), seconds](const CommandOutcome& outcome) {
        if (self.isNull()) return;
        if (!outcome.ok) {
          self->message_->setText(tr("Interval refused: %1").arg(outcome.reason));
        } else {
          self->message_->setText(seconds > 0 ? tr("A photo every %1 s").arg(seconds)
                                              : tr("Interval photos off"));
        }
      });
}

void PhotosPanel::receive(const kapfix::v1::Photo& chunk) {
  std::optional<SavedPhoto> saved;
  try {
    saved = store_.add(chunk);
  } catch (const std::runtime_error& error) {
    message_->setText(tr("Cannot save the photo: %1").arg(QString::fromUtf8(error.what())));
    return;
  }
  if (!saved) return;
  message_->setText(tr("Saved %1").arg(saved->image_path));
  const QString name = QString::fromStdString(saved->metadata.file_name());
  if (!shown_.contains(name)) {
    shown_.insert(name);
    QImage image(saved->image_path);
    auto* item = new QListWidgetItem(name);
    if (!image.isNull()) {
      item->setIcon(
          QPixmap::fromImage(image.scaledToHeight(kThumbnailPx, Qt::SmoothTransformation)));
    }
    item->setData(Qt::UserRole, saved->image_path);
    const QString flags = QString::fromStdString(JudgePhoto(saved->metadata).flags);
    item->setToolTip(tr("%1\nslice %2, confidence %3")
                         .arg(saved->image_path)
                         .arg(saved->metadata.slice())
                         .arg(static_cast<double>(saved->metadata.confidence()), 0, 'f', 2) +
                     (flags.isEmpty() ? QString() : QStringLiteral("\n") + flags));
    if (!flags.isEmpty()) item->setForeground(QColor(0xb3, 0x26, 0x1e));
    gallery_->addItem(item);
    gallery_->scrollToItem(item);
    quality_->addPhoto(*saved);
  }
  emit photoSaved(*saved);
}

}  // namespace kapfix::station
