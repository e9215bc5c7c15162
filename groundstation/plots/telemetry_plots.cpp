#include "groundstation/plots/telemetry_plots.hpp"

#include <qcustomplot.h>

#include <QFile>
#include <QFileDialog>
#include <QLabel>
#include <QMouseEvent>
#include <QSaveFile>
#include <QToolBar>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace kapfix::station {
namespace {

constexpr int kRects = 4;  // residual, confidence, SSD distance, servos

struct CurveStyle {
  int rect;          // which stacked plot: 0 residual, 1 confidence, 2 distance, 3 servos
  const char* name;  // legend text
  QColor colour;
  Qt::PenStyle style;
};

const std::array<CurveStyle, TelemetryPlots::kCurveCount> kCurves = {{
    {0, QT_TRANSLATE_NOOP("TelemetryPlots", "x [px]"), QColor(31, 119, 180), Qt::SolidLine},
    {0, QT_TRANSLATE_NOOP("TelemetryPlots", "y [px]"), QColor(214, 39, 40), Qt::SolidLine},
    {1, QT_TRANSLATE_NOOP("TelemetryPlots", "confidence [0..1]"), QColor(44, 160, 44),
     Qt::SolidLine},
    {2, QT_TRANSLATE_NOOP("TelemetryPlots", "SSD [grey²]"), QColor(148, 103, 189), Qt::SolidLine},
    {3, QT_TRANSLATE_NOOP("TelemetryPlots", "pan cmd [deg]"), QColor(255, 127, 14), Qt::DashLine},
    {3, QT_TRANSLATE_NOOP("TelemetryPlots", "tilt cmd"), QColor(23, 190, 207), Qt::DashLine},
    {3, QT_TRANSLATE_NOOP("TelemetryPlots", "pan [deg]"), QColor(255, 127, 14), Qt::SolidLine},
    {3, QT_TRANSLATE_NOOP("TelemetryPlots", "tilt"), QColor(23, 190, 207), Qt::SolidLine},
}};

// Share of the height of each plot; the legends beside them name the curves with their units
// (axis titles would not fit the small plots of a laptop screen).
const std::array<double, kRects> kRectStretch = {1.8, 0.7, 0.7, 0.9};
const std::array<int, kRects> kRectTicks = {2, 2, 2, 2};
constexpr int kTickRows = 3;  // tick labels each plot has room for, one above the other

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

// One of the stacked plots, row `i` of the plot's layout, its margins aligned with the others';
// only the lowest shows the time axis, titled `time_label`.
QCPAxisRect* AddStackedRect(QCustomPlot* plot, QCPMarginGroup* margins, int i, const QFont& small,
                            const QString& time_label) {
  const auto at = static_cast<std::size_t>(i);
  auto* rect = new QCPAxisRect(plot);
  plot->plotLayout()->addElement(i, 0, rect);
  rect->setMarginGroup(QCP::msLeft | QCP::msRight, margins);
  rect->axis(QCPAxis::atLeft)->ticker()->setTickCount(kRectTicks[at]);
  rect->axis(QCPAxis::atLeft)->setTickLabelFont(small);
  rect->axis(QCPAxis::atBottom)->setTickLabelFont(small);
  rect->setMinimumMargins(QMargins(0, 2, 0, 2));
  // Room for three tick labels one above the other (the ±10 px scale's -10, 0, 10), so
  // that they do not overlap however large the font (issue 14).
  rect->setMinimumSize(0, kTickRows * QFontMetrics(small).height() + 4);
  rect->axis(QCPAxis::atBottom)->setLabel(i == kRects - 1 ? time_label : QString());
  rect->axis(QCPAxis::atBottom)->setTickLabels(i == kRects - 1);
  rect->setRangeZoom(Qt::Horizontal | Qt::Vertical);
  return rect;
}

// The legend of row `i`, in the column beside its plot.
QCPLegend* AddLegend(QCustomPlot* plot, int i, const QFont& small) {
  auto* legend = new QCPLegend;
  plot->plotLayout()->addElement(i, 1, legend);
  legend->setLayer(QStringLiteral("legend"));
  legend->setFont(small);
  legend->setRowSpacing(0);
  legend->setBorderPen(Qt::NoPen);
  legend->setMargins(QMargins(4, 0, 4, 0));
  legend->setFillOrder(QCPLayoutGrid::foRowsFirst);  // two rows, then a new column
  legend->setWrap(2);
  legend->setIconSize(16, 8);
  return legend;
}

}  // namespace

TelemetryPlots::TelemetryPlots(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      plot_(new QCustomPlot(this)),
      pause_(new QAction(tr("Pause"), this)),
      follow_(new QAction(tr("Follow"), this)),
      state_(new QLabel(this)) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(makeToolbar());
  layout->addWidget(plot_, 1);
  makePlots();

  connect(&client, &AgentClient::telemetryReceived, this, &TelemetryPlots::addSample);
  redraw_timer_.setInterval(1000 / kRedrawHz);
  connect(&redraw_timer_, &QTimer::timeout, this, &TelemetryPlots::redraw);
  redraw_timer_.start();
  showState();
}

QToolBar* TelemetryPlots::makeToolbar() {
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
  state_->setObjectName(QStringLiteral("plotState"));
  state_->setTextFormat(Qt::PlainText);
  state_->setMargin(3);
  QFont bold = state_->font();
  bold.setBold(true);
  state_->setFont(bold);
  toolbar->addSeparator();
  toolbar->addWidget(state_);

  connect(pause_, &QAction::toggled, this, [this](bool paused) {
    showState();
    if (!paused) redraw();
  });
  connect(follow_, &QAction::toggled, this, [this](bool on) {
    showState();
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
  return toolbar;
}

void TelemetryPlots::makePlots() {
  // Four stacked axis rects with aligned margins and one shared time axis; each legend in
  // the column beside its plot.
  plot_->plotLayout()->clear();
  auto* margins = new QCPMarginGroup(plot_);
  std::array<QCPAxisRect*, kRects> rects{};
  std::array<QCPLegend*, kRects> legends{};
  QFont small = font();
  small.setPointSizeF(small.pointSizeF() * 0.85);
  plot_->plotLayout()->setRowSpacing(0);
  for (int i = 0; i < kRects; ++i) {
    rects[static_cast<std::size_t>(i)] =
        AddStackedRect(plot_, margins, i, small, tr("capture time [s]"));
    legends[static_cast<std::size_t>(i)] = AddLegend(plot_, i, small);
    plot_->plotLayout()->setRowStretchFactor(i, kRectStretch[static_cast<std::size_t>(i)]);
  }
  plot_->plotLayout()->setColumnStretchFactor(1, 0.01);  // the legends take what they need
  // The widget asks for the plots' room plus the time axis' ticks and title below them: a
  // dock squeezed below it would stack the plots over each other.
  plot_->setMinimumHeight(kRects * (kTickRows * QFontMetrics(small).height() + 4) +
                          2 * QFontMetrics(font()).height() + 8);
  rects[1]->axis(QCPAxis::atLeft)->setRange(0, 1.05);
  // The distance reaches 10⁷..10⁸: short "5e+07"-style labels, few of them.
  rects[2]->axis(QCPAxis::atLeft)->setNumberFormat(QStringLiteral("gb"));
  rects[2]->axis(QCPAxis::atLeft)->setNumberPrecision(2);
  rects[0]->axis(QCPAxis::atLeft)->setRange(-kResidualScalePx, kResidualScalePx);
  for (int i = 0; i < kRects; ++i) {
    connect(rects[static_cast<std::size_t>(i)]->axis(QCPAxis::atBottom),
            qOverload<const QCPRange&>(&QCPAxis::rangeChanged), this,
            [rects, i](const QCPRange& range) {
              for (int j = 0; j < kRects; ++j) {
                if (j != i)
                  rects[static_cast<std::size_t>(j)]->axis(QCPAxis::atBottom)->setRange(range);
              }
            });
  }
  for (int c = 0; c < kCurveCount; ++c) {
    const CurveStyle& style = kCurves[static_cast<std::size_t>(c)];
    QCPAxisRect* rect = rects[static_cast<std::size_t>(style.rect)];
    QCPGraph* graph = plot_->addGraph(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    graph->setName(tr(style.name));
    graph->setPen(QPen(style.colour, 1.6, style.style));
    graph->removeFromLegend(plot_->legend);
    graph->addToLegend(legends[static_cast<std::size_t>(style.rect)]);
    graphs_[static_cast<std::size_t>(c)] = graph;
  }
  plot_->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
  plot_->setNoAntialiasingOnDrag(true);
  // Dragging or zooming means the operator wants to look at something: stop following, and
  // say so above the plots. A plain click (press and release in place) changes nothing.
  connect(plot_, &QCustomPlot::mouseMove, this, [this](QMouseEvent* event) {
    if (event->buttons() != Qt::NoButton) follow_->setChecked(false);
  });
  connect(plot_, &QCustomPlot::mouseWheel, this, [this] { follow_->setChecked(false); });
}

QString TelemetryPlots::stateText() const { return state_->text(); }

QCPRange TelemetryPlots::residualRange() const {
  return graphs_[static_cast<std::size_t>(Curve::kDisplacementX)]->valueAxis()->range();
}

void TelemetryPlots::showState() {
  QString colour;
  if (pause_->isChecked()) {
    state_->setText(tr("PAUSED: the graphs are frozen, data is still collected (P resumes)"));
    colour = QStringLiteral("#b35c00");
  } else if (!follow_->isChecked()) {
    state_->setText(tr("NOT FOLLOWING: the newest data may be off-screen (F follows)"));
    colour = QStringLiteral("#b35c00");
  } else {
    state_->setText(tr("LIVE · session %1").arg(series_.session()));
    colour = QStringLiteral("#1e7b34");
  }
  state_->setStyleSheet(
      QStringLiteral("QLabel { color: white; background: %1; border-radius: 3px; }").arg(colour));
}

void TelemetryPlots::fitResidual() {
  // ±kResidualScalePx unless something larger is in view: one spike widens the scale only
  // while it is on screen.
  const QCPRange keys = graphs_[0]->keyAxis()->range();
  double largest = 0;
  for (const Curve curve : {Curve::kDisplacementX, Curve::kDisplacementY}) {
    const auto points = graphs_[static_cast<std::size_t>(curve)]->data();
    for (auto it = points->findBegin(keys.lower, false);
         it != points->end() && it->key <= keys.upper; ++it) {
      largest = std::max(largest, std::abs(it->value));
    }
  }
  const double half = largest <= kResidualScalePx ? kResidualScalePx : largest * 1.1;
  graphs_[0]->valueAxis()->setRange(-half, half);
}

void TelemetryPlots::startSession() {
  series_.startSession();
  drawn_ = series_.appended();
  for (QCPGraph* graph : graphs_) graph->data()->clear();
  showState();
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

QCPGraph* TelemetryPlots::graph(Curve curve) const {
  return graphs_[static_cast<std::size_t>(curve)];
}

void TelemetryPlots::addSample(const kapfix::v1::Telemetry& telemetry) {
  const int session = series_.session();
  series_.append(telemetry);
  if (series_.session() != session) {
    // The capture clock went back: the graphs start again rather than draw two clocks.
    for (QCPGraph* graph : graphs_) graph->data()->clear();
    drawn_ = series_.appended() - 1;
    showState();
  }
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
  if (!samples.empty() && samples.front().session == series_.session()) {
    const double oldest = samples.front().time_s;
    for (QCPGraph* graph : graphs_) graph->data()->removeBefore(oldest);
  }
  if (follow_->isChecked() && !samples.empty()) {
    const double newest = samples.back().time_s;
    graphs_[0]->keyAxis()->setRange(std::max(0.0, newest - kFollowWindowS),
                                    std::max(kFollowWindowS, newest));
    fitResidual();
    for (const Curve curve : {Curve::kDistance, Curve::kPan}) {
      // Pan and tilt share their axis: rescaling it for one fits all four servo curves.
      graphs_[static_cast<std::size_t>(curve)]->valueAxis()->rescale(true);
    }
  }
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

void TelemetryPlots::clear() {
  series_.clear();
  drawn_ = 0;
  showState();
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
