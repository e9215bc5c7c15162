#pragma once

// Every slice's displacement graph from the last SSP run, as small multiples (same axes, so
// they compare at a glance): one small plot per slice, titled with its index and DC count,
// the recommended slice framed. Clicking a plot picks that slice.

#include <QWidget>
#include <vector>

#include "kapfix/v1/slices.pb.h"

class QCustomPlot;
class QGridLayout;

namespace kapfix::station {

class SliceGraphGrid final : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kColumns = 3;

  explicit SliceGraphGrid(QWidget* parent = nullptr);

  void showReport(const kapfix::v1::SliceReport& report);
  // The plot of slice `index` (1 = top), nullptr if none.
  QCustomPlot* plotOf(unsigned index) const;
  unsigned highlighted() const { return highlighted_; }

 signals:
  void sliceClicked(unsigned index);

 private:
  QGridLayout* grid_;
  std::vector<QCustomPlot*> plots_;  // index 0 = slice 1
  unsigned highlighted_ = 0;
};

}  // namespace kapfix::station
