#include "groundstation/recording/recording_controls.hpp"

#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QSettings>
#include <QStandardPaths>
#include <QToolButton>
#include <utility>

namespace kapfix::station {
namespace {

QString SessionsFolder() {
  const QString fallback = QDir(QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation))
                               .filePath(QStringLiteral("kapfix-sessions"));
  return QSettings().value(QStringLiteral("recording/folder"), fallback).toString();
}

constexpr int kMessageWidthEm = 22;  // [characters] the message never pushes the toolbar

QToolButton* Button(QAction* action, QWidget* parent) {
  auto* button = new QToolButton(parent);
  button->setDefaultAction(action);
  button->setToolButtonStyle(Qt::ToolButtonTextOnly);
  return button;
}

}  // namespace

RecordingControls::RecordingControls(AgentClient& live, QWidget* parent)
    : QWidget(parent),
      recording_(live),
      record_(new QAction(tr("● Record"), this)),
      replay_(new QAction(tr("Replay…"), this)),
      play_(new QAction(tr("Play"), this)),
      live_action_(new QAction(tr("Live"), this)),
      speed_(new QComboBox(this)),
      message_(new QLabel(this)) {
  record_->setCheckable(true);
  record_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_R));
  record_->setToolTip(
      tr("Start or stop recording telemetry, video and events into the photos folder (Ctrl+R)"));
  replay_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_O));
  replay_->setToolTip(tr("Replay a recorded session in a window of its own (Ctrl+O)"));
  play_->setCheckable(true);
  play_->setToolTip(tr("Play or pause the replay"));
  live_action_->setToolTip(tr("Close the replay"));
  for (const double speed : {0.5, 1.0, 2.0, 4.0, 10.0}) {
    speed_->addItem(QStringLiteral("%1×").arg(speed), speed);
  }
  speed_->setCurrentIndex(1);

  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(Button(record_, this));
  layout->addWidget(Button(replay_, this));
  layout->addWidget(Button(play_, this));
  layout->addWidget(speed_);
  layout->addWidget(Button(live_action_, this));
  message_->setObjectName(QStringLiteral("recordingMessage"));
  message_->setFixedWidth(message_->fontMetrics().averageCharWidth() * kMessageWidthEm);
  layout->addWidget(message_);

  connect(record_, &QAction::triggered, this, &RecordingControls::toggleRecording);
  connect(replay_, &QAction::triggered, this, &RecordingControls::chooseReplay);
  connect(play_, &QAction::triggered, this, [this](bool on) {
    if (on) {
      replay_client_.play();
    } else {
      replay_client_.pause();
    }
    showState();
  });
  connect(live_action_, &QAction::triggered, this, &RecordingControls::backToLive);
  connect(speed_, &QComboBox::currentIndexChanged, this,
          [this] { replay_client_.setSpeed(speed_->currentData().toDouble()); });
  connect(&replay_client_, &ReplayAgentClient::finished, this, &RecordingControls::showState);
  connect(&recording_, &SessionRecording::failed, this,
          [this](const QString& reason) { setMessage(tr("Recording stopped: %1").arg(reason)); });
  connect(&recording_, &SessionRecording::recordingChanged, this, &RecordingControls::showState);
  showState();
}

bool RecordingControls::startRecording(const QString& path, QString* error) {
  QString why;
  const bool ok = recording_.start(path, &why);
  if (!ok) setMessage(tr("Cannot record: %1").arg(why));
  if (error != nullptr) *error = why;
  showState();
  return ok;
}

void RecordingControls::stopRecording() {
  if (!recording_.recording()) return;
  recording_.stop();
  setMessage(tr("Recorded %1").arg(QFileInfo(recording_.path()).fileName()),
             QDir::toNativeSeparators(recording_.path()));
  showState();
}

bool RecordingControls::startReplay(const QString& path, QString* error) {
  stopRecording();
  QString why;
  if (!replay_client_.open(path, &why)) {
    setMessage(tr("Cannot replay: %1").arg(why));
    if (error != nullptr) *error = why;
    return false;
  }
  replaying_ = true;
  emit replayStarted();  // its window connects before anything is delivered
  replay_client_.setSpeed(speed_->currentData().toDouble());
  replay_client_.play();
  setMessage(QString());
  showState();
  return true;
}

void RecordingControls::backToLive() {
  replay_client_.close();
  const bool was_replaying = std::exchange(replaying_, false);
  showState();
  if (was_replaying) emit replayClosed();
}

QString RecordingControls::startRecordingInFolder() {
  const QString folder = folder_ ? folder_() : SessionsFolder();
  QDir().mkpath(folder);
  const QString path = QDir(folder).filePath(
      QStringLiteral("session-%1.kfxrec")
          .arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-HHmmss"))));
  return startRecording(path) ? path : QString();
}

QString RecordingControls::messageText() const { return message_text_; }

void RecordingControls::setMessage(const QString& text, const QString& tooltip) {
  message_text_ = text;
  message_->setText(message_->fontMetrics().elidedText(text, Qt::ElideMiddle, message_->width()));
  message_->setToolTip(tooltip.isEmpty() ? text : tooltip);
}

void RecordingControls::toggleRecording(bool on) {
  if (on) {
    startRecordingInFolder();
  } else {
    stopRecording();
  }
}

void RecordingControls::chooseReplay() {
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Replay a session"), SessionsFolder(),
                                   tr("kapfix recording (*.kfxrec);;All files (*)"));
  if (!path.isEmpty()) startReplay(path);
}

void RecordingControls::showState() {
  const bool replaying = replaying_;
  record_->setChecked(recording_.recording());
  record_->setEnabled(!replaying);
  record_->setText(recording_.recording() ? tr("■ Stop recording") : tr("● Record"));
  play_->setEnabled(replaying && !replay_client_.atEnd());
  play_->setChecked(replay_client_.playing());
  play_->setText(replay_client_.playing() ? tr("Pause") : tr("Play"));
  speed_->setEnabled(replaying);
  live_action_->setEnabled(replaying);
  if (recording_.recording()) {
    setMessage(tr("● REC %1").arg(QFileInfo(recording_.path()).fileName()),
               QDir::toNativeSeparators(recording_.path()));
  } else if (replaying && replay_client_.atEnd()) {
    setMessage(tr("Replay finished"));
  }
}

}  // namespace kapfix::station
