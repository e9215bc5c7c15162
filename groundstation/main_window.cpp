#include "groundstation/main_window.hpp"

#include <QCloseEvent>
#include <QDockWidget>
#include <QMenuBar>
#include <QSettings>
#include <QStatusBar>
#include <QToolBar>

#include "groundstation/events/event_log.hpp"
#include "groundstation/photos/photos_panel.hpp"
#include "groundstation/plots/telemetry_plots.hpp"
#include "groundstation/recording/recording_controls.hpp"
#include "groundstation/settings/calibration_view.hpp"
#include "groundstation/settings/settings_panel.hpp"
#include "groundstation/slices/ssp_panel.hpp"
#include "groundstation/status/connection_bar.hpp"
#include "groundstation/status/link_status_bar.hpp"
#include "groundstation/video/video_panel.hpp"

namespace kapfix::station {
namespace {

QDockWidget* Dock(QMainWindow* window, const QString& title, const QString& name,
                  QWidget* content) {
  auto* dock = new QDockWidget(title, window);
  dock->setObjectName(name);  // restoreState() finds docks by name
  dock->setWidget(content);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                    QDockWidget::DockWidgetClosable);
  return dock;
}

}  // namespace

MainWindow::MainWindow(const MainWindowParts& parts, QWidget* parent)
    : QMainWindow(parent),
      video_(new VideoPanel(*parts.view_client, this)),
      plots_(new TelemetryPlots(*parts.view_client, this)),
      ssp_(new SspPanel(*parts.view_client, this)),
      settings_(new SettingsPanel(*parts.view_client, this)),
      photos_(new PhotosPanel(*parts.view_client, this)),
      events_(new EventLog(*parts.view_client, this)),
      status_(new LinkStatusBar(*parts.view_client, this)) {
  setWindowTitle(tr("kapfix station"));
  setCentralWidget(video_);
  setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks);
  // The side panels run the full height: the slice table and its graphs need it more than
  // the time graphs need the full width.
  setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
  setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
  resize(1600, 1000);

  auto* plots_dock = Dock(this, tr("Graphs"), QStringLiteral("graphsDock"), plots_);
  addDockWidget(Qt::BottomDockWidgetArea, plots_dock);
  auto* ssp_dock = Dock(this, tr("Slice selection"), QStringLiteral("sspDock"), ssp_);
  auto* settings_dock = Dock(this, tr("Settings"), QStringLiteral("settingsDock"), settings_);
  auto* photos_dock = Dock(this, tr("Photos"), QStringLiteral("photosDock"), photos_);
  auto* events_dock = Dock(this, tr("Events"), QStringLiteral("eventsDock"), events_);
  addDockWidget(Qt::RightDockWidgetArea, ssp_dock);
  tabifyDockWidget(ssp_dock, settings_dock);
  tabifyDockWidget(settings_dock, photos_dock);
  tabifyDockWidget(photos_dock, events_dock);
  ssp_dock->raise();
  resizeDocks({ssp_dock}, {540}, Qt::Horizontal);
  resizeDocks({plots_dock}, {400}, Qt::Vertical);
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

  // Menus: every shortcut in one place where the operator can look it up.
  QMenu* station = menuBar()->addMenu(tr("&Station"));
  if (parts.connection != nullptr) {
    station->addAction(tr("Agent address"), QKeySequence(Qt::CTRL | Qt::Key_L),
                       &parts.connection->hostEdit(),
                       [connection = parts.connection] { connection->hostEdit().setFocus(); });
  }
  station->addSeparator();
  station->addAction(tr("Quit"), QKeySequence::Quit, this, &QWidget::close);

  QMenu* agent = menuBar()->addMenu(tr("&Agent"));
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

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(plots_->pauseAction());
  view->addAction(plots_->followAction());
  view->addSeparator();
  for (QDockWidget* dock : {plots_dock, ssp_dock, settings_dock, photos_dock, events_dock}) {
    view->addAction(dock->toggleViewAction());
  }
  view->addSeparator();
  view->addAction(tr("Full screen"), QKeySequence(Qt::Key_F11), this,
                  [this] { setWindowState(windowState() ^ Qt::WindowFullScreen); });

  if (parts.recording != nullptr) {
    QMenu* session = menuBar()->addMenu(tr("S&ession"));
    session->addAction(parts.recording->recordAction());
    session->addAction(parts.recording->replayAction());
    session->addAction(parts.recording->playAction());
    session->addAction(parts.recording->liveAction());
  }
  // Window-wide shortcuts also when their menu entry is not visible.
  addActions({ssp_->runAction(), ssp_->confirmAction(), photos_->captureAction(),
              plots_->pauseAction(), plots_->followAction()});

  const QSettings settings;
  restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray());
  restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
}

MainWindow::~MainWindow() = default;

void MainWindow::closeEvent(QCloseEvent* event) {
  QSettings settings;
  settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
  settings.setValue(QStringLiteral("window/state"), saveState());
  QMainWindow::closeEvent(event);
}

}  // namespace kapfix::station
