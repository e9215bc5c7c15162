#pragma once

// The full-width line at the top of the window for what must not be missed: the link down
// (with how long since the agent was last heard), a restarted agent (a new session: Idle,
// its settings perhaps back to defaults, or resumed from its stored state), a replay, or a
// question waiting for Enter. The most urgent one shows; a restart stays until the operator
// dismisses it.

#include <QElapsedTimer>
#include <QLabel>
#include <QPushButton>
#include <QTimer>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class SessionBanner final : public QWidget {
  Q_OBJECT

 public:
  explicit SessionBanner(AgentClient& client, QWidget* parent = nullptr);

  // A restarted agent: shown until dismissed (or the next restart).
  void announceRestart(int session);
  // A question the operator answers with Enter (empty: none).
  void setPrompt(const QString& prompt);

  QString text() const { return label_->text(); }
  QPushButton& dismissButton() const { return *dismiss_; }

 private:
  void refresh();
  QString restartText() const;

  QLabel* label_;
  QPushButton* dismiss_;
  LinkState link_;
  bool heard_ = false;            // the link was up at least once
  QElapsedTimer last_heard_;      // since the agent's last message
  int restart_session_ = 0;       // the restarted session announced, until dismissed; 0 = none
  QString restart_time_;          // when it was noticed, "HH:mm:ss"
  kapfix::v1::AgentState state_;  // the agent's latest: did it resume, in which mode
  QString prompt_;
  QTimer tick_;  // refreshes the age while the link is down
};

}  // namespace kapfix::station
