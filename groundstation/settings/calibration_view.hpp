#pragma once

// Calibration for the operator (SPEC §2.7): run it, follow its progress, and see the result
// per axis — the fitted servo degrees per pixel (and the thesis's median), drawn as the line
// it implies with a band of ± its RMS residual.

#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"

class QCustomPlot;

namespace kapfix::station {

class CalibrationView final : public QWidget {
  Q_OBJECT

 public:
  explicit CalibrationView(AgentClient& client, QWidget* parent = nullptr);

  void showReport(const kapfix::v1::CalibrationReport& report);
  QString resultText() const { return result_->text(); }
  QString messageText() const { return message_->text(); }
  QPushButton& runButton() const { return *run_; }

 private:
  void run();

  AgentClient& client_;
  QPushButton* run_;
  QProgressBar* progress_;
  QLabel* result_;
  QLabel* message_;
  QCustomPlot* plot_;
};

}  // namespace kapfix::station
