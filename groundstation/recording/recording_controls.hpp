#pragma once

// Record and replay (issue 4, 14), as toolbar actions: one key (Ctrl+R) starts and stops
// recording what the live views show, into the photos folder under an automatic name (no
// dialog over the video); open a recording and replay it, with no agent (play/pause, speed),
// in a window of its own (replayStarted): the live views and graphs are never touched.

#include <QAction>
#include <QComboBox>
#include <QLabel>
#include <QWidget>
#include <functional>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/recording/replay_agent_client.hpp"
#include "groundstation/recording/session_recording.hpp"

namespace kapfix::station {

class RecordingControls final : public QWidget {
  Q_OBJECT

 public:
  // `live`: what is recorded (the live agent, as the window's panels see it).
  explicit RecordingControls(AgentClient& live, QWidget* parent = nullptr);

  QAction* recordAction() const { return record_; }
  QAction* replayAction() const { return replay_; }
  QAction* playAction() const { return play_; }
  QAction* liveAction() const { return live_action_; }
  SessionRecording& recording() { return recording_; }
  ReplayAgentClient& replay() { return replay_client_; }

  // Where Ctrl+R records to (the photos folder); without it, the last sessions folder.
  void setFolderSource(std::function<QString()> folder) { folder_ = std::move(folder); }
  // Starts recording into the folder under an automatic name; the path, or "" on failure.
  QString startRecordingInFolder();
  bool replaying() const { return replaying_; }
  QString messageText() const;

  // Without dialogs: start recording into `path`, or replay the file at `path`.
  bool startRecording(const QString& path, QString* error = nullptr);
  void stopRecording();
  bool startReplay(const QString& path, QString* error = nullptr);
  void backToLive();

 signals:
  // A replay was opened: show replay() somewhere of its own.
  void replayStarted();
  // The replay was closed (back to live only).
  void replayClosed();

 private:
  void toggleRecording(bool on);
  void setMessage(const QString& text, const QString& tooltip = QString());
  void chooseReplay();
  void showState();

  SessionRecording recording_;
  ReplayAgentClient replay_client_;
  QAction* record_;
  QAction* replay_;
  QAction* play_;
  QAction* live_action_;
  QComboBox* speed_;
  QLabel* message_;
  QString message_text_;  // the full message; the label shows it elided
  std::function<QString()> folder_;
  bool replaying_ = false;
};

}  // namespace kapfix::station
