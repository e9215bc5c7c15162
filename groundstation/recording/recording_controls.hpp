#pragma once

// Record and replay (issue 4), as toolbar actions: record what the views show to a file;
// open a recording and replay it in the same views, with no agent (play/pause, speed); go
// back to the live agent. Switching is SwitchableAgentClient's: the panels never notice.

#include <QAction>
#include <QComboBox>
#include <QLabel>
#include <QWidget>

#include "groundstation/client/switchable_agent_client.hpp"
#include "groundstation/recording/replay_agent_client.hpp"
#include "groundstation/recording/session_recording.hpp"

namespace kapfix::station {

class RecordingControls final : public QWidget {
  Q_OBJECT

 public:
  // `views` is what the panels watch; `live` the agent link it returns to.
  RecordingControls(SwitchableAgentClient& views, AgentClient& live, QWidget* parent = nullptr);

  QAction* recordAction() const { return record_; }
  QAction* replayAction() const { return replay_; }
  QAction* playAction() const { return play_; }
  QAction* liveAction() const { return live_action_; }
  SessionRecording& recording() { return recording_; }
  ReplayAgentClient& replay() { return replay_client_; }

  // Without dialogs: start recording into `path`, or replay the file at `path`.
  bool startRecording(const QString& path, QString* error = nullptr);
  void stopRecording();
  bool startReplay(const QString& path, QString* error = nullptr);
  void backToLive();

 private:
  void toggleRecording(bool on);
  void chooseReplay();
  void showState();

  SwitchableAgentClient& views_;
  AgentClient& live_;
  SessionRecording recording_;
  ReplayAgentClient replay_client_;
  QAction* record_;
  QAction* replay_;
  QAction* play_;
  QAction* live_action_;
  QComboBox* speed_;
  QLabel* message_;
};

}  // namespace kapfix::station
