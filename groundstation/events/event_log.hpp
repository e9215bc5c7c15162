#pragma once

// The session's events in words, newest last (issue 14: state changes only, no noise): the
// link going up or down (once per change), the agent's mode and slice changing, refusals with
// the agent's reason, photos received, finished SSP and calibration runs (one line each), and
// the agent's warnings and errors. Commands the operator sent are not repeated here: their
// effect (a mode change, a refusal) is. Bounded, so a long flight stays light.

#include <QPlainTextEdit>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class EventLog final : public QPlainTextEdit {
  Q_OBJECT

 public:
  static constexpr int kMaxLines = 2000;

  explicit EventLog(AgentClient& client, QWidget* parent = nullptr);

  void addLine(const QString& text, const QColor& colour = QColor());
  // The lines shown, oldest first, without their time stamps.
  QStringList lines() const;

 private:
  void showLink(const LinkState& state);
  void showMode(kapfix::v1::Mode mode, unsigned slice);
  void showPhoto(const kapfix::v1::Photo& chunk);

  bool link_known_ = false;
  bool link_up_ = false;
  bool replay_ = false;
  kapfix::v1::Mode mode_ = kapfix::v1::MODE_UNSPECIFIED;
  unsigned slice_ = 0;
};

// One line for a finished SSP: the recommended slice with its scores, e.g. "SSP finished: slice
// 8 recommended (DC 24, FFT 5.33 k) of 9 slices after 400 frames".
QString SspResultLine(const kapfix::v1::SliceReport& report);

}  // namespace kapfix::station
