#include "groundstation/settings/calibration_view.hpp"

#include <qcustomplot.h>

#include <QPointer>
#include <QVBoxLayout>
#include <cmath>

namespace kapfix::station {
namespace {

constexpr double kServoSpanDeg = 10.0;  // [deg] the plot shows servo moves of ± this

QString AxisText(const QString& name, const kapfix::v1::AxisCalibration& axis) {
  if (!axis.valid())
    return QObject::tr("%1: no valid fit (%2 moves)").arg(name).arg(axis.samples());
  return QObject::tr("%1: %2 deg/px (median %3), residual %4 px, %5 moves")
      .arg(name)
      .arg(axis.units_per_px_fit(), 0, 'f', 4)
      .arg(axis.units_per_px_median(), 0, 'f', 4)
      .arg(axis.residual_px(), 0, 'f', 2)
      .arg(axis.samples());
}

}  // namespace

CalibrationView::CalibrationView(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      client_(client),
      run_(new QPushButton(tr("Run calibration"), this)),
      progress_(new QProgressBar(this)),
      result_(new QLabel(tr("No calibration yet"), this)),
      message_(new QLabel(this)),
      plot_(new QCustomPlot(this)) {
  run_->setToolTip(tr("Move the servos by known amounts and measure the view's displacement"));
  progress_->setRange(0, 1);
  progress_->setValue(0);
  result_->setObjectName(QStringLiteral("calibrationResult"));
  result_->setWordWrap(true);
  message_->setWordWrap(true);
  message_->setStyleSheet(QStringLiteral("color: #b3261e;"));
  plot_->setMinimumHeight(140);
  plot_->xAxis->setLabel(tr("servo move [deg]"));
  plot_->yAxis->setLabel(tr("displacement [px]"));
  plot_->legend->setVisible(true);
  plot_->legend->setFont(QFont(font().family(), 8));
  plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* row = new QHBoxLayout;
  row->addWidget(run_);
  row->addWidget(progress_, 1);
  layout->addLayout(row);
  layout->addWidget(result_);
  layout->addWidget(message_);
  layout->addWidget(plot_, 1);

  connect(run_, &QPushButton::clicked, this, &CalibrationView::run);
  connect(&client_, &AgentClient::calibrationReceived, this, &CalibrationView::showReport);
  connect(&client_, &AgentClient::stateReceived, this, [this](const kapfix::v1::AgentState& state) {
    if (state.has_calibration()) showReport(state.calibration());
  });
}

void CalibrationView::run() {
  kapfix::v1::Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_CALIBRATE);
  message_->clear();
  client_.sendCommand(std::move(command), [self = QPointer(this)](const CommandOutcome& outcome) {
    if (self.isNull()) return;
    self->message_->setText(outcome.ok ? QString() : tr("Refused: %1").arg(outcome.reason));
  });
}

void CalibrationView::showReport(const kapfix::v1::CalibrationReport& report) {
  progress_->setRange(0, static_cast<int>(std::max<std::uint32_t>(1, report.progress_total())));
  progress_->setValue(static_cast<int>(report.progress_done()));
  if (!report.finished()) {
    result_->setText(tr("Calibrating %1: %2 of %3 moves")
                         .arg(QString::fromStdString(report.lens_profile()))
                         .arg(report.progress_done())
                         .arg(report.progress_total()));
    return;
  }
  result_->setText(tr("Lens %1\n%2\n%3")
                       .arg(QString::fromStdString(report.lens_profile()))
                       .arg(AxisText(tr("Pan"), report.pan()))
                       .arg(AxisText(tr("Tilt"), report.tilt())));
  plot_->clearGraphs();
  const std::array<std::pair<QString, const kapfix::v1::AxisCalibration*>, 2> axes = {
      {{tr("pan"), &report.pan()}, {tr("tilt"), &report.tilt()}}};
  const std::array<QColor, 2> colours = {QColor(255, 127, 14), QColor(23, 190, 207)};
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const kapfix::v1::AxisCalibration& axis = *axes[a].second;
    if (!axis.valid() || axis.units_per_px_fit() == 0.0) continue;
    // The fit says px = deg / (deg/px); the band is ± the RMS residual around it.
    const double px_per_deg = 1.0 / axis.units_per_px_fit();
    const QVector<double> keys = {-kServoSpanDeg, kServoSpanDeg};
    for (const int side : {0, -1, 1}) {
      QCPGraph* graph = plot_->addGraph();
      const double offset = side * axis.residual_px();
      graph->setData(keys,
                     {-kServoSpanDeg * px_per_deg + offset, kServoSpanDeg * px_per_deg + offset});
      graph->setPen(
          QPen(colours[a], side == 0 ? 2.0 : 1.0, side == 0 ? Qt::SolidLine : Qt::DotLine));
      if (side == 0) {
        graph->setName(tr("%1 fit").arg(axes[a].first));
      } else {
        graph->removeFromLegend();
      }
    }
  }
  plot_->rescaleAxes();
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace kapfix::station
