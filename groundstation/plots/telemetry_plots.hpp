#pragma once

// Live graphs of the telemetry (issue 4, 14): the residual displacement x and y, confidence,
// SSD distance, servo angles (commanded and reached), against the agent's capture time, in
// four stacked plots sharing the time axis, legends beside them (never over the newest
// data). Samples are collected all the time; the plots redraw at most kRedrawHz. They follow
// the newest data until the operator drags or zooms (a plain click changes nothing), and can
// be paused; either state is written in words above the plots. The residual keeps a fixed
// ±kResidualScalePx scale that grows for larger values in view and shrinks back once they
// leave it. Each agent session starts the graphs afresh (startSession); the CSV export keeps
// every session's samples, each with its number. Export: PNG of the plots, CSV.

#include <QAction>
#include <QTimer>
#include <QWidget>
#include <array>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/plots/telemetry_series.hpp"

class QCustomPlot;
class QCPGraph;
class QCPRange;
class QLabel;
class QToolBar;

namespace kapfix::station {

class TelemetryPlots final : public QWidget {
  Q_OBJECT

 public:
  enum class Curve {
    kDisplacementX,
    kDisplacementY,
    kConfidence,
    kDistance,  // its own small plot: its scale is nothing like the confidence's
    kPanTarget,
    kTiltTarget,
    kPan,
    kTilt,
  };
  static constexpr int kCurveCount = 8;
  static constexpr int kRedrawHz = 20;              // [Hz]
  static constexpr double kFollowWindowS = 20.0;    // [s] time span shown while following
  static constexpr double kResidualScalePx = 10.0;  // [px] the residual plot's least half-range

  explicit TelemetryPlots(AgentClient& client, QWidget* parent = nullptr);

  const TelemetrySeries& series() const { return series_; }
  QCPGraph* graph(Curve curve) const;
  QCustomPlot* plot() const { return plot_; }

  QAction* pauseAction() const { return pause_; }
  QAction* followAction() const { return follow_; }
  // "LIVE", "PAUSED …" or "NOT FOLLOWING …": what the state line above the plots says.
  QString stateText() const;
  // [px] the residual plot's value range as drawn.
  QCPRange residualRange() const;

  // Brings the graphs up to date now (the timer does it otherwise); nothing while paused.
  void redraw();
  bool exportPng(const QString& path) const;
  bool exportCsv(const QString& path) const;
  void clear();
  // A new agent session: the graphs start empty on its own time origin.
  void startSession();

 private:
  QToolBar* makeToolbar();  // the actions above the plots and the state label, connected
  void makePlots();         // the four stacked plots, their legends and curves
  void showState();
  void fitResidual();
  void addSample(const kapfix::v1::Telemetry& telemetry);
  void chooseExport(bool png);

  TelemetrySeries series_;
  std::uint64_t drawn_ = 0;  // [count] samples already in the graphs
  bool dirty_ = false;
  QCustomPlot* plot_;
  std::array<QCPGraph*, kCurveCount> graphs_{};
  QAction* pause_;
  QAction* follow_;
  QLabel* state_;
  QTimer redraw_timer_;
};

}  // namespace kapfix::station
