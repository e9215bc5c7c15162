#pragma once

// Live graphs of the telemetry (issue 4): displacement x and y, confidence and distance,
// servo angles (commanded and reached), against time, in three stacked plots sharing the
// time axis. Samples are collected all the time; the plots redraw at most kRedrawHz, follow
// the newest data unless the operator zooms or drags, and can be paused. Export: PNG of the
// plots, CSV of every sample held.

#include <QAction>
#include <QTimer>
#include <QWidget>
#include <array>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/plots/telemetry_series.hpp"

class QCustomPlot;
class QCPGraph;

namespace kapfix::station {

class TelemetryPlots final : public QWidget {
  Q_OBJECT

 public:
  enum class Curve {
    kDisplacementX,
    kDisplacementY,
    kConfidence,
    kDistance,
    kPanTarget,
    kTiltTarget,
    kPan,
    kTilt,
  };
  static constexpr int kCurveCount = 8;
  static constexpr int kRedrawHz = 20;            // [Hz]
  static constexpr double kFollowWindowS = 20.0;  // [s] time span shown while following

  explicit TelemetryPlots(AgentClient& client, QWidget* parent = nullptr);

  const TelemetrySeries& series() const { return series_; }
  QCPGraph* graph(Curve curve) const;
  QCustomPlot* plot() const { return plot_; }

  QAction* pauseAction() const { return pause_; }
  QAction* followAction() const { return follow_; }

  // Brings the graphs up to date now (the timer does it otherwise); nothing while paused.
  void redraw();
  bool exportPng(const QString& path) const;
  bool exportCsv(const QString& path) const;
  void clear();

 private:
  void addSample(const kapfix::v1::Telemetry& telemetry);
  void chooseExport(bool png);

  TelemetrySeries series_;
  std::uint64_t drawn_ = 0;  // [count] samples already in the graphs
  bool dirty_ = false;
  QCustomPlot* plot_;
  std::array<QCPGraph*, kCurveCount> graphs_{};
  QAction* pause_;
  QAction* follow_;
  QTimer redraw_timer_;
};

}  // namespace kapfix::station
