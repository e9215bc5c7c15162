#pragma once

// The station's window: lays the panels out (video in the centre, graphs below, SSP,
// settings, photos and events as docked tabs, link status at the bottom) and collects their
// keyboard shortcuts in menus. It holds no logic of its own: each panel talks to the agent
// through the AgentClient it is given.

#include <QMainWindow>

namespace kapfix::station {

class AgentClient;
class ConnectionBar;
class EventLog;
class LinkStatusBar;
class PhotosPanel;
class RecordingControls;
class SettingsPanel;
class SspPanel;
class TelemetryPlots;
class VideoPanel;

// What the window shows; built by main (or a test) and handed in.
struct MainWindowParts {
  AgentClient* view_client = nullptr;      // what every panel watches (live or replay)
  ConnectionBar* connection = nullptr;     // optional: agent address and connect
  RecordingControls* recording = nullptr;  // optional: record and replay
};

class MainWindow final : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(const MainWindowParts& parts, QWidget* parent = nullptr);
  ~MainWindow() override;

  VideoPanel& video() const { return *video_; }
  TelemetryPlots& plots() const { return *plots_; }
  SspPanel& ssp() const { return *ssp_; }
  SettingsPanel& settings() const { return *settings_; }
  PhotosPanel& photos() const { return *photos_; }
  EventLog& events() const { return *events_; }
  LinkStatusBar& status() const { return *status_; }

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  VideoPanel* video_;
  TelemetryPlots* plots_;
  SspPanel* ssp_;
  SettingsPanel* settings_;
  PhotosPanel* photos_;
  EventLog* events_;
  LinkStatusBar* status_;
};

}  // namespace kapfix::station
