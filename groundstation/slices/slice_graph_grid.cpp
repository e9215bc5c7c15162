#include "groundstation/slices/slice_graph_grid.hpp"

#include <qcustomplot.h>

#include <QGridLayout>
#include <algorithm>

namespace kapfix::station {

SliceGraphGrid::SliceGraphGrid(QWidget* parent) : QWidget(parent), grid_(new QGridLayout(this)) {
  grid_->setContentsMargins(0, 0, 0, 0);
  grid_->setSpacing(4);
}

QCustomPlot* SliceGraphGrid::plotOf(unsigned index) const {
  if (index == 0 || index > plots_.size()) return nullptr;
  return plots_[index - 1];
}

void SliceGraphGrid::showReport(const kapfix::v1::SliceReport& report) {
  const auto count = static_cast<std::size_t>(report.slices_size());
  while (plots_.size() > count) {
    delete plots_.back();
    plots_.pop_back();
  }
  while (plots_.size() < count) {
    auto* plot = new QCustomPlot(this);
    plot->setMinimumSize(120, 90);
    plot->plotLayout()->insertRow(0);
    auto* title = new QCPTextElement(plot, QString(), QFont(font().family(), -1, QFont::Bold));
    plot->plotLayout()->addElement(0, 0, title);
    plot->addGraph();
    plot->xAxis->setTickLabels(false);
    plot->yAxis->setTickLabelFont(QFont(font().family(), 7));
    const auto index = static_cast<unsigned>(plots_.size() + 1);
    connect(plot, &QCustomPlot::mousePress, this, [this, index] { emit sliceClicked(index); });
    const int row = static_cast<int>(plots_.size()) / kColumns;
    const int column = static_cast<int>(plots_.size()) % kColumns;
    grid_->addWidget(plot, row, column);
    plots_.push_back(plot);
  }

  // One value range for all, so a calm slice looks calm next to a jumpy one.
  double low = -1;
  double high = 1;
  int longest = 1;
  for (const auto& slice : report.slices()) {
    for (const float v : slice.graph_px()) {
      low = std::min(low, static_cast<double>(v));
      high = std::max(high, static_cast<double>(v));
    }
    longest = std::max(longest, slice.graph_px_size());
  }
  highlighted_ = report.recommended_slice();
  for (std::size_t i = 0; i < count; ++i) {
    const auto& slice = report.slices(static_cast<int>(i));
    QCustomPlot* plot = plots_[i];
    QVector<double> keys;
    QVector<double> values;
    keys.reserve(slice.graph_px_size());
    values.reserve(slice.graph_px_size());
    for (int t = 0; t < slice.graph_px_size(); ++t) {
      keys.push_back(t + 1);
      values.push_back(slice.graph_px(t));
    }
    const bool best = slice.index() == highlighted_;
    plot->graph(0)->setData(keys, values, true);
    plot->graph(0)->setPen(QPen(best ? QColor(30, 123, 52) : QColor(60, 60, 60), best ? 1.6 : 1.0));
    plot->xAxis->setRange(1, longest);
    plot->yAxis->setRange(low, high);
    auto* title = qobject_cast<QCPTextElement*>(plot->plotLayout()->element(0, 0));
    title->setText(
        tr("%1 · DC %2%3").arg(slice.index()).arg(slice.dc()).arg(best ? tr(" ★") : QString()));
    title->setTextColor(best ? QColor(30, 123, 52) : Qt::black);
    plot->setBackground(best ? QBrush(QColor(228, 244, 231)) : QBrush(Qt::white));
    plot->axisRect()->setBackground(best ? QBrush(QColor(228, 244, 231)) : QBrush(Qt::white));
    plot->replot(QCustomPlot::rpQueuedReplot);
  }
}

}  // namespace kapfix::station
