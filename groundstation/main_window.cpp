#include "groundstation/main_window.hpp"

#include <QCloseEvent>
#include <QDockWidget>
#include <QGuiApplication>
#include <QMenuBar>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QTabBar>
#include <QToolBar>
#include <QVBoxLayout>
#include <algorithm>

#include "groundstation/events/event_log.hpp"
#include "groundstation/keys/lock_confirmation.hpp"
#include "groundstation/keys/priority_keys.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/plots/telemetry_plots.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/session/session_banner.hpp"
#include "groundstation/session/session_tracker.hpp"
#include "groundstation/settings/calibration_view.hpp"
#include "groundstation/settings/settings_panel.hpp"
#include "groundstation/settings/settings_reapply_offer.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/connection_bar.hpp"
#include "groundstation/status/device_health_view.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "groundstation/status/lock_indicator.hpp"
#include "groundstation/status/lock_monitor.hpp"
#include "groundstation/video/video_panel.hpp"

namespace kapfix::station {
namespace {

constexpr double kSideShare = 0.30;    // of the window's width, for the tabbed side panels
constexpr double kGraphsShare = 0.34;  // of the window's height, for the graphs
constexpr int kSideMaxPx = 540;        // [px] the side panels need no more
constexpr int kGraphsMaxPx = 400;      // [px]

enum class Fit { kScroll, kSqueeze };

QDockWidget* Dock(QMainWindow* window, const QString& title, const QString& name, QWidget* content,
                  Fit fit = Fit::kScroll) {
  auto* dock = new QDockWidget(title, window);
  dock->setObjectName(name);  // restoreState() finds docks by name
  if (fit == Fit::kScroll) {
    // Scrolled rather than squeezed: a panel's minimum never pushes the window off a small
    // screen or takes the video's room.
    auto* scroll = new QScrollArea(dock);
    scroll->setWidget(content);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    dock->setWidget(scroll);
  } else {
    dock->setWidget(content);  // it draws in whatever room it gets (the graphs)
  }
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                    QDockWidget::DockWidgetClosable);
  return dock;
}

}  // namespace

MainWindow::MainWindow(const MainWindowParts& parts, QWidget* parent)
    : QMainWindow(parent),
      settings_group_(parts.settings_group),
      sessions_(new SessionTracker(*parts.view_client, this)),
      video_(new VideoPanel(*parts.view_client, this)),
      plots_(new TelemetryPlots(*parts.view_client, this)),
      ssp_(new SspPanel(*parts.view_client, this)),
      settings_(new SettingsPanel(*parts.view_client, this)),
      photos_(new PhotosPanel(*parts.view_client, this)),
      events_(new EventLog(*parts.view_client, this)),
      status_(new LinkStatusBar(*parts.view_client, this)),
      devices_(new DeviceHealthView(*parts.view_client, this)),
      lock_(new LockMonitor(*parts.view_client, LockQualityOptions{}, this)),
      lock_on_video_(new LockIndicator(*lock_, LockIndicator::Size::kOnVideo, this)),
      lock_in_status_(new LockIndicator(*lock_, LockIndicator::Size::kStatusBar, this)),
      banner_(new SessionBanner(*parts.view_client, this)),
      confirmation_(new LockConfirmation(*parts.view_client, *this, this)),
      reapply_(new SettingsReapplyOffer(*parts.view_client, *settings_, this)) {
  // Space takes the photo even from inside a number field (which keeps its value); Enter and
  // Esc answer a pending question from there too (with none pending they reach the field).
  new PriorityKeys(*this,
                   {QKeySequence(Qt::Key_Space), QKeySequence(Qt::Key_Return),
                    QKeySequence(Qt::Key_Enter), QKeySequence(Qt::Key_Escape)},
                   this);
  setWindowTitle(tr("kapfix station"));
  setCentralWidget(video_);
  video_->setCornerWidget(lock_on_video_);
  setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks);
  // The side panels run the full height: the slice table and its graphs need it more than
  // the time graphs need the full width.
  setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
  setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
  const QScreen* screen = QGuiApplication::primaryScreen();
  const QSize room =
      screen != nullptr ? screen->availableGeometry().size() : QSize(kDefaultWidth, kDefaultHeight);
  resize(std::min(kDefaultWidth, room.width()), std::min(kDefaultHeight, room.height()));

  plots_dock_ = Dock(this, tr("Graphs"), QStringLiteral("graphsDock"), plots_, Fit::kSqueeze);
  addDockWidget(Qt::BottomDockWidgetArea, plots_dock_);
  // Short tab titles: four side by side fit the side panel with a large font too.
  auto* ssp_dock = Dock(this, tr("Slices"), QStringLiteral("sspDock"), ssp_);
  auto* settings_dock = Dock(this, tr("Settings"), QStringLiteral("settingsDock"), settings_);
  auto* photos_dock = Dock(this, tr("Photos"), QStringLiteral("photosDock"), photos_);
  auto* events_dock = Dock(this, tr("Events"), QStringLiteral("eventsDock"), events_);
  addDockWidget(Qt::RightDockWidgetArea, ssp_dock);
  tabifyDockWidget(ssp_dock, settings_dock);
  tabifyDockWidget(settings_dock, photos_dock);
  tabifyDockWidget(photos_dock, events_dock);
  ssp_dock->raise();
  side_dock_ = ssp_dock;
  statusBar()->addWidget(lock_in_status_);
  statusBar()->addWidget(devices_);
  statusBar()->addWidget(status_, 1);

  auto* toolbar = addToolBar(tr("Station"));
  toolbar->setObjectName(QStringLiteral("stationToolbar"));
  toolbar->setMovable(false);
  if (parts.connection != nullptr) {
    toolbar->addWidget(parts.connection);
    toolbar->addSeparator();
  }
  toolbar->addAction(ssp_->runAction());
  toolbar->addAction(photos_->captureAction());
  if (parts.recording != nullptr) {
    toolbar->addSeparator();
    toolbar->addWidget(parts.recording);
  }
  // The banner under the menus, across the window's full width (over the docks too).
  auto* menus = new QMenuBar;
  auto* top = new QWidget(this);
  auto* top_layout = new QVBoxLayout(top);
  top_layout->setContentsMargins(0, 0, 0, 0);
  top_layout->setSpacing(0);
  top_layout->addWidget(menus);
  top_layout->addWidget(banner_);
  top_layout->addWidget(reapply_);
  setMenuWidget(top);

  ssp_->setConfirmation(confirmation_);
  video_->setConfirmation(confirmation_);
  connect(confirmation_, &LockConfirmation::promptChanged, banner_, &SessionBanner::setPrompt);
  connect(sessions_, &SessionTracker::sessionStarted, this, &MainWindow::startNewSession);
  if (parts.recording != nullptr) {
    parts.recording->setFolderSource([this] { return photos_->folder(); });
    connect(parts.recording, &RecordingControls::replayStarted, this,
            [this, recording = parts.recording] { showReplay(*recording); });
    connect(parts.recording, &RecordingControls::replayClosed, this,
            [this] { replay_window_.reset(); });
  }
  buildMenus(*menus, parts);

  const QSettings settings;
  restoreGeometry(settings.value(settings_group_ + QStringLiteral("/geometry")).toByteArray());
  restoreState(settings.value(settings_group_ + QStringLiteral("/state")).toByteArray());
  shareSpace();
}

MainWindow::~MainWindow() = default;

void MainWindow::buildMenus(QMenuBar& menus, const MainWindowParts& parts) {
  // Menus: every shortcut in one place where the operator can look it up.
  QMenu* station = menus.addMenu(tr("&Station"));
  if (parts.connection != nullptr) {
    station->addAction(tr("Agent address"), QKeySequence(Qt::CTRL | Qt::Key_L),
                       &parts.connection->hostEdit(),
                       [connection = parts.connection] { connection->hostEdit().setFocus(); });
  }
  station->addSeparator();
  station->addAction(tr("Quit"), QKeySequence::Quit, this, &QWidget::close);

  QMenu* agent = menus.addMenu(tr("&Agent"));
  agent->addAction(ssp_->runAction());
  agent->addAction(ssp_->confirmAction());
  QMenu* slices = agent->addMenu(tr("Fixate on slice"));
  for (unsigned i = 1; i <= 9; ++i) {
    slices->addAction(tr("Slice %1").arg(i),
                      QKeySequence(static_cast<int>(Qt::CTRL) | static_cast<int>(Qt::Key_0 + i)),
                      ssp_, [this, i] { ssp_->pickSlice(i); });
  }
  agent->addAction(photos_->captureAction());
  agent->addAction(tr("Run calibration"), settings_,
                   [this] { settings_->calibration().runButton().click(); });

  QMenu* view = menus.addMenu(tr("&View"));
  view->addAction(plots_->pauseAction());
  view->addAction(plots_->followAction());
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());
  view->addSeparator();
  QAction* beep = view->addAction(tr("Beep when the lock is lost"));
  beep->setCheckable(true);
  beep->setChecked(lock_->audible());
  connect(beep, &QAction::toggled, lock_, &LockMonitor::setAudible);
  view->addAction(tr("Full screen"), QKeySequence(Qt::Key_F11), this,
                  [this] { setWindowState(windowState() ^ Qt::WindowFullScreen); });

  if (parts.recording != nullptr) {
    QMenu* session = menus.addMenu(tr("S&ession"));
    session->addAction(parts.recording->recordAction());
    session->addAction(parts.recording->replayAction());
    session->addAction(parts.recording->playAction());
    session->addAction(parts.recording->liveAction());
  }
  // Window-wide shortcuts also when their menu entry is not visible.
  addActions({ssp_->runAction(), ssp_->confirmAction(), photos_->captureAction(),
              plots_->pauseAction(), plots_->followAction()});
}

void MainWindow::startNewSession(int session, bool restart) {
  if (!restart) return;  // the first agent heard: nothing to clear
  banner_->announceRestart(session);
  events_->addLine(
      tr("AGENT RESTARTED: new session %1; the old one's results are cleared").arg(session),
      QColor(179, 92, 0));
  ssp_->clearSession();
  video_->clearSession();
  plots_->startSession();
  lock_->reset();
  confirmation_->cancel();
  reapply_->arm();
}

void MainWindow::showReplay(RecordingControls& recording) {
  MainWindowParts parts;
  parts.view_client = &recording.replay();
  parts.settings_group = QStringLiteral("replayWindow");
  replay_window_ = std::make_unique<MainWindow>(parts);
  replay_window_->setWindowTitle(tr("kapfix station: REPLAY (not live)"));
  // Closing the replay's window ends the replay (later: not from inside its own close event).
  connect(replay_window_.get(), &MainWindow::closed, &recording, &RecordingControls::backToLive,
          Qt::QueuedConnection);
  replay_window_->show();
}

void MainWindow::shareSpace() {
  if (side_dock_ == nullptr || plots_dock_ == nullptr) return;
  // A tab title is never cut short: where the tabs do not fit, the bar scrolls instead.
  for (QTabBar* tabs : findChildren<QTabBar*>()) {
    tabs->setElideMode(Qt::ElideNone);
    tabs->setUsesScrollButtons(true);
  }
  resizeDocks({side_dock_}, {std::min(kSideMaxPx, static_cast<int>(width() * kSideShare))},
              Qt::Horizontal);
  resizeDocks({plots_dock_}, {std::min(kGraphsMaxPx, static_cast<int>(height() * kGraphsShare))},
              Qt::Vertical);
}

void MainWindow::resizeEvent(QResizeEvent* event) {
  QMainWindow::resizeEvent(event);
  shareSpace();
}

void MainWindow::closeEvent(QCloseEvent* event) {
  QSettings settings;
  settings.setValue(settings_group_ + QStringLiteral("/geometry"), saveGeometry());
  settings.setValue(settings_group_ + QStringLiteral("/state"), saveState());
  QMainWindow::closeEvent(event);
  emit closed();
}

}  // namespace kapfix::station
