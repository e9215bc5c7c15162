#pragma once

// The session's events in words, newest last: link changes, the operator's commands and
// what the agent answered (refusals with their reason), finished SSP and calibration runs,
// and the agent's log lines (info and above). Bounded, so a long flight stays light.

#include <QPlainTextEdit>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class EventLog final : public QPlainTextEdit {
  Q_OBJECT

 public:
  static constexpr int kMaxLines = 2000;

  explicit EventLog(AgentClient& client, QWidget* parent = nullptr);

  void addLine(const QString& text, const QColor& colour = QColor());
};

}  // namespace kapfix::station
