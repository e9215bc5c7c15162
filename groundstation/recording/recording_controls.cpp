#include "groundstation/recording/recording_controls.hpp"

#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QSettings>
#include <QStandardPaths>
#include <QToolButton>

namespace kapfix::station {
namespace {

QString SessionsFolder() {
  const QString fallback = QDir(QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation))
                               .filePath(QStringLiteral("kapfix-sessions"));
  return QSettings().value(QStringLiteral("recording/folder"), fallback).toString();
}

QToolButton* Button(QAction* action, QWidget* parent) {
  auto* button = new QToolButton(parent);
  button->setDefaultAction(action);
  button->setToolButtonStyle(Qt::ToolButtonTextOnly);
  return button;
}

}  // namespace

RecordingControls::RecordingControls(SwitchableAgentClient& views, AgentClient& live,
                                     QWidget* parent)
    : QWidget(parent),
      views_(views),
      live_(live),
      recording_(views),
      record_(new QAction(tr("● Record"), this)),
      replay_(new QAction(tr("Replay…"), this)),
      play_(new QAction(tr("Play"), this)),
      live_action_(new QAction(tr("Live"), this)),
      speed_(new QComboBox(this)),
      message_(new QLabel(this)) {
  record_->setCheckable(true);
  record_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_R));
  record_->setToolTip(tr("Record telemetry, video and events to a file (Ctrl+R)"));
  replay_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_O));
  replay_->setToolTip(tr("Replay a recorded session in these views, without an agent (Ctrl+O)"));
  play_->setCheckable(true);
  play_->setToolTip(tr("Play or pause the replay"));
  live_action_->setToolTip(tr("Back to the live agent"));
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
  connect(&recording_, &SessionRecording::failed, this, [this](const QString& reason) {
    message_->setText(tr("Recording stopped: %1").arg(reason));
  });
  connect(&recording_, &SessionRecording::recordingChanged, this, &RecordingControls::showState);
  showState();
}

bool RecordingControls::startRecording(const QString& path, QString* error) {
  QString why;
  const bool ok = recording_.start(path, &why);
  if (!ok) message_->setText(tr("Cannot record: %1").arg(why));
  if (error != nullptr) *error = why;
  showState();
  return ok;
}

void RecordingControls::stopRecording() {
  if (!recording_.recording()) return;
  recording_.stop();
  message_->setText(tr("Recorded to %1").arg(QDir::toNativeSeparators(recording_.path())));
  showState();
}

bool RecordingControls::startReplay(const QString& path, QString* error) {
  stopRecording();
  QString why;
  if (!replay_client_.open(path, &why)) {
    message_->setText(tr("Cannot replay: %1").arg(why));
    if (error != nullptr) *error = why;
    return false;
  }
  views_.setSource(replay_client_);
  replay_client_.setSpeed(speed_->currentData().toDouble());
  replay_client_.play();
  message_->clear();
  showState();
  return true;
}

void RecordingControls::backToLive() {
  replay_client_.close();
  views_.setSource(live_);
  showState();
}

void RecordingControls::toggleRecording(bool on) {
  if (!on) {
    stopRecording();
    return;
  }
  const QString folder = SessionsFolder();
  QDir().mkpath(folder);
  const QString suggested = QDir(folder).filePath(
      QStringLiteral("session-%1.kfxrec")
          .arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-HHmmss"))));
  const QString path = QFileDialog::getSaveFileName(this, tr("Record session to"), suggested,
                                                    tr("kapfix recording (*.kfxrec)"));
  if (path.isEmpty()) {
    showState();
    return;
  }
  QSettings().setValue(QStringLiteral("recording/folder"), QFileInfo(path).absolutePath());
  startRecording(path);
}

void RecordingControls::chooseReplay() {
  const QString path =
      QFileDialog::getOpenFileName(this, tr("Replay a session"), SessionsFolder(),
                                   tr("kapfix recording (*.kfxrec);;All files (*)"));
  if (!path.isEmpty()) startReplay(path);
}

void RecordingControls::showState() {
  const bool replaying = &views_.source() == &replay_client_;
  record_->setChecked(recording_.recording());
  record_->setEnabled(!replaying);
  record_->setText(recording_.recording() ? tr("■ Stop recording") : tr("● Record"));
  play_->setEnabled(replaying && !replay_client_.atEnd());
  play_->setChecked(replay_client_.playing());
  play_->setText(replay_client_.playing() ? tr("Pause") : tr("Play"));
  speed_->setEnabled(replaying);
  live_action_->setEnabled(replaying);
  if (recording_.recording()) {
    message_->setText(tr("Recording to %1").arg(QFileInfo(recording_.path()).fileName()));
  } else if (replaying && replay_client_.atEnd()) {
    message_->setText(tr("Replay finished"));
  }
}

}  // namespace kapfix::station
