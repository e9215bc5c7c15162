#pragma once

// The always-visible line at the bottom of the window (issue 4): link state, latency, agent
// fps, mode, slice in use, and which agent or recording the views show. Large type: it is
// read at arm's length in daylight. While the link is down the agent's values stay, greyed:
// they are the last heard, not the present.

#include <QLabel>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class LinkStatusBar final : public QWidget {
  Q_OBJECT

 public:
  explicit LinkStatusBar(AgentClient& client, QWidget* parent = nullptr);

  // What the labels say, for tests and screen readers.
  QString linkText() const { return link_->text(); }
  QString latencyText() const { return latency_->text(); }
  QString fpsText() const { return fps_->text(); }
  QString modeText() const { return mode_->text(); }
  // Link down: fps, mode and slice are the last heard, greyed (issue 14).
  bool valuesGreyed() const { return greyed_; }

 private:
  void showLink(const LinkState& state);
  void showTelemetry(const kapfix::v1::Telemetry& telemetry);
  void showMode(kapfix::v1::Mode mode);

  QLabel* link_;
  QLabel* latency_;
  QLabel* fps_;
  QLabel* mode_;
  QLabel* slice_;
  QLabel* source_;
  bool greyed_ = false;
  bool resumed_ = false;  // the agent's state says it resumed from its stored state
};

}  // namespace kapfix::station
