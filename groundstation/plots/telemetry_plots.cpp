#include "groundstation/plots/telemetry_plots.hpp"

#include <qcustomplot.h>

#include <QFile>
#include <QFileDialog>
#include <QSaveFile>
#include <QToolBar>
#include <QVBoxLayout>

namespace kapfix::station {
namespace {

struct CurveStyle {
  int rect;          // which stacked plot: 0 displacement, 1 quality, 2 servos
  bool right_axis;   // drawn against the plot's right axis
  const char* name;  // legend text
  QColor colour;
  Qt::PenStyle style;
};

const std::array<CurveStyle, TelemetryPlots::kCurveCount> kCurves = {{
    {0, false, QT_TRANSLATE_NOOP("TelemetryPlots", "x [px]"), QColor(31, 119, 180), Qt::SolidLine},
    {0, false, QT_TRANSLATE_NOOP("TelemetryPlots", "y [px]"), QColor(214, 39, 40), Qt::SolidLine},
    {1, false, QT_TRANSLATE_NOOP("TelemetryPlots", "confidence"), QColor(44, 160, 44),
     Qt::SolidLine},
    {1, true, QT_TRANSLATE_NOOP("TelemetryPlots", "SSD distance (right)"), QColor(148, 103, 189),
     Qt::SolidLine},
    {2, false, QT_TRANSLATE_NOOP("TelemetryPlots", "pan cmd [deg]"), QColor(255, 127, 14),
     Qt::DashLine},
    {2, false, QT_TRANSLATE_NOOP("TelemetryPlots", "tilt cmd [deg]"), QColor(23, 190, 207),
     Qt::DashLine},
    {2, false, QT_TRANSLATE_NOOP("TelemetryPlots", "pan [deg]"), QColor(255, 127, 14),
     Qt::SolidLine},
    {2, false, QT_TRANSLATE_NOOP("TelemetryPlots", "tilt [deg]"), QColor(23, 190, 207),
     Qt::SolidLine},
}};

const std::array<const char*, 3> kRectTitles = {
    QT_TRANSLATE_NOOP("TelemetryPlots", "[px]"),
    QT_TRANSLATE_NOOP("TelemetryPlots", "[0..1]"),
    QT_TRANSLATE_NOOP("TelemetryPlots", "[deg]"),
};

double Value(const TelemetrySample& sample, int curve) {
  switch (static_cast<TelemetryPlots::Curve>(curve)) {
    case TelemetryPlots::Curve::kDisplacementX:
      return sample.x_px;
    case TelemetryPlots::Curve::kDisplacementY:
      return sample.y_px;
    case TelemetryPlots::Curve::kConfidence:
      return sample.confidence;
    case TelemetryPlots::Curve::kDistance:
      return sample.distance;
    case TelemetryPlots::Curve::kPanTarget:
      return sample.pan_target_deg;
    case TelemetryPlots::Curve::kTiltTarget:
      return sample.tilt_target_deg;
    case TelemetryPlots::Curve::kPan:
      return sample.pan_deg;
    case TelemetryPlots::Curve::kTilt:
      return sample.tilt_deg;
  }
  return 0;
}

}  // namespace

TelemetryPlots::TelemetryPlots(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      plot_(new QCustomPlot(this)),
      pause_(new QAction(tr("Pause"), this)),
      follow_(new QAction(tr("Follow"), this)) {
  pause_->setCheckable(true);
  pause_->setShortcut(QKeySequence(Qt::Key_P));
  pause_->setToolTip(tr("Freeze the graphs; data is still collected (P)"));
  follow_->setCheckable(true);
  follow_->setChecked(true);
  follow_->setShortcut(QKeySequence(Qt::Key_F));
  follow_->setToolTip(
      tr("Show the newest %1 s; off while you zoom or drag (F)").arg(kFollowWindowS));
  auto* reset = new QAction(tr("Reset zoom"), this);
  auto* png = new QAction(tr("Export PNG…"), this);
  auto* csv = new QAction(tr("Export CSV…"), this);
  auto* clear_action = new QAction(tr("Clear"), this);

  auto* toolbar = new QToolBar(this);
  toolbar->setToolButtonStyle(Qt::ToolButtonTextOnly);
  for (QAction* action : {pause_, follow_, reset, png, csv, clear_action}) {
    toolbar->addAction(action);
  }
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(toolbar);
  layout->addWidget(plot_, 1);

  // Three stacked axis rects with aligned left margins and one shared time axis.
  plot_->plotLayout()->clear();
  auto* margins = new QCPMarginGroup(plot_);
  std::array<QCPAxisRect*, 3> rects{};
  for (int i = 0; i < 3; ++i) {
    auto* rect = new QCPAxisRect(plot_);
    plot_->plotLayout()->addElement(i, 0, rect);
    rect->setMarginGroup(QCP::msLeft | QCP::msRight, margins);
    rect->axis(QCPAxis::atLeft)->setLabel(tr(kRectTitles[static_cast<std::size_t>(i)]));
    rect->axis(QCPAxis::atBottom)->setLabel(i == 2 ? tr("time [s]") : QString());
    rect->setRangeZoom(Qt::Horizontal | Qt::Vertical);
    auto* legend = new QCPLegend;
    rect->insetLayout()->addElement(legend, Qt::AlignTop | Qt::AlignRight);
    legend->setLayer(QStringLiteral("legend"));
    legend->setBrush(QColor(255, 255, 255, 210));
    legend->setFillOrder(QCPLayoutGrid::foColumnsFirst);  // one row: keeps the curves visible
    QFont small = font();
    small.setPointSizeF(small.pointSizeF() * 0.85);
    legend->setFont(small);
    legend->setRowSpacing(0);
    legend->setColumnSpacing(6);
    rects[static_cast<std::size_t>(i)] = rect;
  }
  rects[1]->axis(QCPAxis::atRight)->setVisible(true);
  rects[1]->axis(QCPAxis::atRight)->setNumberFormat(QStringLiteral("gb"));
  rects[1]->axis(QCPAxis::atLeft)->setRange(0, 1.05);
  for (int i = 0; i < 3; ++i) {
    connect(rects[static_cast<std::size_t>(i)]->axis(QCPAxis::atBottom),
            qOverload<const QCPRange&>(&QCPAxis::rangeChanged), this,
            [rects, i](const QCPRange& range) {
              for (int j = 0; j < 3; ++j) {
                if (j != i)
                  rects[static_cast<std::size_t>(j)]->axis(QCPAxis::atBottom)->setRange(range);
              }
            });
  }
  for (int c = 0; c < kCurveCount; ++c) {
    const CurveStyle& style = kCurves[static_cast<std::size_t>(c)];
    QCPAxisRect* rect = rects[static_cast<std::size_t>(style.rect)];
    QCPGraph* graph =
        plot_->addGraph(rect->axis(QCPAxis::atBottom),
                        rect->axis(style.right_axis ? QCPAxis::atRight : QCPAxis::atLeft));
    graph->setName(tr(style.name));
    graph->setPen(QPen(style.colour, 1.6, style.style));
    graph->removeFromLegend(plot_->legend);
    graph->addToLegend(qobject_cast<QCPLegend*>(rect->insetLayout()->elementAt(0)));
    graphs_[static_cast<std::size_t>(c)] = graph;
  }
  plot_->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
  plot_->setNoAntialiasingOnDrag(true);
  // Zooming or dragging means the operator wants to look at something: stop following.
  connect(plot_, &QCustomPlot::mousePress, this, [this] { follow_->setChecked(false); });
  connect(plot_, &QCustomPlot::mouseWheel, this, [this] { follow_->setChecked(false); });
  connect(pause_, &QAction::toggled, this, [this](bool paused) {
    if (!paused) redraw();
  });
  connect(follow_, &QAction::toggled, this, [this](bool on) {
    if (on) {
      dirty_ = true;
      redraw();
    }
  });
  connect(reset, &QAction::triggered, this, [this] {
    follow_->setChecked(true);
    dirty_ = true;
    redraw();
  });
  connect(png, &QAction::triggered, this, [this] { chooseExport(true); });
  connect(csv, &QAction::triggered, this, [this] { chooseExport(false); });
  connect(clear_action, &QAction::triggered, this, &TelemetryPlots::clear);

  connect(&client, &AgentClient::telemetryReceived, this, &TelemetryPlots::addSample);
  redraw_timer_.setInterval(1000 / kRedrawHz);
  connect(&redraw_timer_, &QTimer::timeout, this, &TelemetryPlots::redraw);
  redraw_timer_.start();
}

QCPGraph* TelemetryPlots::graph(Curve curve) const {
  return graphs_[static_cast<std::size_t>(curve)];
}

void TelemetryPlots::addSample(const kapfix::v1::Telemetry& telemetry) {
  series_.append(telemetry);
  dirty_ = true;
}

void TelemetryPlots::redraw() {
  if (pause_->isChecked() || !dirty_) return;
  dirty_ = false;
  const auto& samples = series_.samples();
  // Only what is not drawn yet; samples the series already dropped are skipped.
  const std::uint64_t missing = series_.appended() - drawn_;
  const std::size_t first =
      missing >= samples.size() ? 0 : samples.size() - static_cast<std::size_t>(missing);
  for (std::size_t i = first; i < samples.size(); ++i) {
    for (int c = 0; c < kCurveCount; ++c) {
      graphs_[static_cast<std::size_t>(c)]->addData(samples[i].time_s, Value(samples[i], c));
    }
  }
  drawn_ = series_.appended();
  if (!samples.empty()) {
    const double oldest = samples.front().time_s;
    for (QCPGraph* graph : graphs_) graph->data()->removeBefore(oldest);
  }
  if (follow_->isChecked() && !samples.empty()) {
    const double newest = samples.back().time_s;
    graphs_[0]->keyAxis()->setRange(std::max(0.0, newest - kFollowWindowS),
                                    std::max(kFollowWindowS, newest));
    for (QCPGraph* graph : graphs_) {
      if (graph != graphs_[static_cast<std::size_t>(Curve::kConfidence)]) {
        graph->valueAxis()->rescale(true);
      }
    }
  }
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

void TelemetryPlots::clear() {
  series_.clear();
  drawn_ = 0;
  for (QCPGraph* graph : graphs_) graph->data()->clear();
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

bool TelemetryPlots::exportPng(const QString& path) const {
  return plot_->savePng(path, 0, 0, 1.0, -1, 96);
}

bool TelemetryPlots::exportCsv(const QString& path) const {
  QSaveFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) return false;
  series_.writeCsv(file);
  return file.commit();
}

void TelemetryPlots::chooseExport(bool png) {
  const QString path = QFileDialog::getSaveFileName(
      this, png ? tr("Export graphs as PNG") : tr("Export telemetry as CSV"),
      png ? QStringLiteral("telemetry.png") : QStringLiteral("telemetry.csv"),
      png ? tr("PNG image (*.png)") : tr("CSV table (*.csv)"));
  if (path.isEmpty()) return;
  if (png) {
    exportPng(path);
  } else {
    exportCsv(path);
  }
}

}  // namespace kapfix::station
