#pragma once

// The station's window: lays the panels out (video in the centre and first served, graphs
// below, SSP, settings, photos and events as docked tabs, link status and lock quality at the
// bottom, a full-width banner at the top for what must not be missed) and collects their
// keyboard shortcuts in menus. It holds no logic of its own: each part talks to the agent
// through the AgentClient it is given, and the window only connects them.

#include <QMainWindow>
#include <QString>
#include <memory>

class QDockWidget;
class QMenuBar;

namespace kapfix::station {

class AgentClient;
class ConnectionBar;
class DeviceHealthView;
class EventLog;
class LinkStatusBar;
class LockConfirmation;
class LockIndicator;
class LockMonitor;
class PhotosPanel;
class PriorityKeys;
class RecordingControls;
class SessionBanner;
class SessionTracker;
class SettingsPanel;
class SettingsReapplyOffer;
class SspPanel;
class TelemetryPlots;
class VideoPanel;

// What the window shows; built by main (or a test) and handed in.
struct MainWindowParts {
  AgentClient* view_client = nullptr;      // what every panel watches (live or replay)
  ConnectionBar* connection = nullptr;     // optional: agent address and connect
  RecordingControls* recording = nullptr;  // optional: record and replay
  // Where the geometry is remembered (QSettings group): a replay window keeps its own.
  QString settings_group = QStringLiteral("window");
};

class MainWindow final : public QMainWindow {
  Q_OBJECT

 public:
  // [px] the default size, when the screen has room (a laptop's 1366×768 gets less).
  static constexpr int kDefaultWidth = 1600;
  static constexpr int kDefaultHeight = 1000;

  explicit MainWindow(const MainWindowParts& parts, QWidget* parent = nullptr);
  ~MainWindow() override;

  VideoPanel& video() const { return *video_; }
  TelemetryPlots& plots() const { return *plots_; }
  SspPanel& ssp() const { return *ssp_; }
  SettingsPanel& settings() const { return *settings_; }
  PhotosPanel& photos() const { return *photos_; }
  EventLog& events() const { return *events_; }
  LinkStatusBar& status() const { return *status_; }
  DeviceHealthView& devices() const { return *devices_; }
  LockMonitor& lock() const { return *lock_; }
  LockIndicator& lockOnVideo() const { return *lock_on_video_; }
  LockIndicator& lockInStatusBar() const { return *lock_in_status_; }
  SessionBanner& banner() const { return *banner_; }
  SessionTracker& sessions() const { return *sessions_; }
  SettingsReapplyOffer& reapplyOffer() const { return *reapply_; }
  LockConfirmation& confirmation() const { return *confirmation_; }
  // The window a replay is shown in; nullptr while none is open.
  MainWindow* replayWindow() const { return replay_window_.get(); }

 signals:
  // The operator closed the window.
  void closed();

 protected:
  void closeEvent(QCloseEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  void buildMenus(QMenuBar& menus, const MainWindowParts& parts);
  void startNewSession(int session, bool restart);
  void showReplay(RecordingControls& recording);
  // The docks take a share of the window, the video the rest: on a small screen the video
  // keeps most of it.
  void shareSpace();

  QString settings_group_;
  // First of the parts to hear the telemetry: a new session is started before any panel
  // takes the new agent's first sample into the old one.
  SessionTracker* sessions_;
  VideoPanel* video_;
  TelemetryPlots* plots_;
  SspPanel* ssp_;
  SettingsPanel* settings_;
  PhotosPanel* photos_;
  EventLog* events_;
  LinkStatusBar* status_;
  DeviceHealthView* devices_;
  LockMonitor* lock_;
  LockIndicator* lock_on_video_;
  LockIndicator* lock_in_status_;
  SessionBanner* banner_;
  LockConfirmation* confirmation_;
  SettingsReapplyOffer* reapply_;
  QDockWidget* plots_dock_ = nullptr;
  QDockWidget* side_dock_ = nullptr;
  std::unique_ptr<MainWindow> replay_window_;
};

}  // namespace kapfix::station
