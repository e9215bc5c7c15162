#include "groundstation/video/video_panel.hpp"

#include <QGridLayout>
#include <QHBoxLayout>
#include <QPointer>
#include <QSettings>
#include <QVBoxLayout>
#include <array>

#include "groundstation/keys/lock_confirmation.hpp"

namespace kapfix::station {
namespace {

struct Switch {
  const char* name;   // object name and settings key
  const char* label;  // what the operator reads
  bool OverlayOptions::*field;
};

const std::array<Switch, 5> kSwitches = {{
    {"overlay_slice_grid", QT_TRANSLATE_NOOP("VideoPanel", "Slice grid"),
     &OverlayOptions::slice_grid},
    {"overlay_chosen_slice", QT_TRANSLATE_NOOP("VideoPanel", "Chosen slice"),
     &OverlayOptions::chosen_slice},
    {"overlay_reference_patch", QT_TRANSLATE_NOOP("VideoPanel", "Reference patch"),
     &OverlayOptions::reference_patch},
    {"overlay_current_match", QT_TRANSLATE_NOOP("VideoPanel", "Current match"),
     &OverlayOptions::current_match},
    {"overlay_crosshair", QT_TRANSLATE_NOOP("VideoPanel", "Crosshair"), &OverlayOptions::crosshair},
}};

QString SettingsKey(const char* name) { return QStringLiteral("video/") + QLatin1String(name); }

}  // namespace

VideoPanel::VideoPanel(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      client_(client),
      view_(new VideoView(this)),
      message_(new QLabel(this)),
      picture_layout_(new QGridLayout) {
  auto* switches = new QHBoxLayout;
  const QSettings settings;
  for (const Switch& entry : kSwitches) {
    auto* box = new QCheckBox(tr(entry.label), this);
    box->setObjectName(QLatin1String(entry.name));
    box->setChecked(settings.value(SettingsKey(entry.name), true).toBool());
    connect(box, &QCheckBox::toggled, this, &VideoPanel::applySwitches);
    switches->addWidget(box);
  }
  switches->addStretch(1);
  message_->setObjectName(QStringLiteral("videoMessage"));
  switches->addWidget(message_);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addLayout(switches);
  // The picture and what floats over its corner share one cell.
  picture_layout_->setContentsMargins(0, 0, 0, 0);
  picture_layout_->addWidget(view_, 0, 0);
  layout->addLayout(picture_layout_, 1);
  applySwitches();

  connect(&client_, &AgentClient::videoFrameReceived, view_, &VideoView::showFrame);
  connect(&client_, &AgentClient::linkChanged, this,
          [this](const LinkState& state) { view_->setStale(!state.up && !state.replay); });
  connect(view_, &VideoView::sliceClicked, this, &VideoPanel::pickSlice);
}

QCheckBox* VideoPanel::overlaySwitch(const QString& name) const {
  return findChild<QCheckBox*>(name);
}

void VideoPanel::applySwitches() {
  OverlayOptions options;
  QSettings settings;
  for (const Switch& entry : kSwitches) {
    const bool on = overlaySwitch(QLatin1String(entry.name))->isChecked();
    options.*entry.field = on;
    settings.setValue(SettingsKey(entry.name), on);
  }
  view_->setOverlayOptions(options);
}

void VideoPanel::setCornerWidget(QWidget* widget) {
  widget->setParent(this);
  // Top right: the slice numbers are on the left, the crosshair in the middle.
  picture_layout_->addWidget(widget, 0, 0, Qt::AlignTop | Qt::AlignRight);
  widget->raise();
}

void VideoPanel::clearSession() {
  view_->clearPicture();
  message_->clear();
}

void VideoPanel::pickSlice(unsigned index) {
  if (confirmation_ == nullptr) {
    sendSlice(index);
    return;
  }
  confirmation_->request(tr("fixate on slice %1").arg(index), [this, index] { sendSlice(index); });
}

void VideoPanel::sendSlice(unsigned index) {
  kapfix::v1::Command command;
  command.set_select_slice(index);
  message_->setText(tr("Slice %1 …").arg(index));
  // The panel may be gone when the reply comes.
  client_.sendCommand(std::move(command), [self = QPointer(this),
                                           index](const CommandOutcome& outcome) {
    if (self.isNull()) return;
    self->message_->setText(outcome.ok ? tr("Slice %1 selected").arg(index)
                                       : tr("Slice %1 refused: %2").arg(index).arg(outcome.reason));
  });
}

}  // namespace kapfix::station
