#pragma once

// Actions that drop or move the present lock (start SSP, pick another slice on the video)
// run at once while the agent is not holding one, and wait for Enter while it is (issue 14:
// one stray key or click must not drop a lock in flight). The question is asked in words;
// Esc or a few seconds without an answer drop it.

#include <QObject>
#include <QShortcut>
#include <QString>
#include <QTimer>
#include <functional>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class LockConfirmation final : public QObject {
  Q_OBJECT

 public:
  static constexpr int kExpiryMs = 8000;  // [ms] an unanswered question is dropped

  // Enter and Esc answer it anywhere in `window`.
  LockConfirmation(AgentClient& client, QWidget& window, QObject* parent = nullptr);

  // Runs `action` now, or, while the agent fixates or follows, asks "Press Enter to `what`".
  void request(const QString& what, std::function<void()> action);
  bool pending() const { return static_cast<bool>(pending_); }
  QString prompt() const { return prompt_; }
  void confirm();
  void cancel();

 signals:
  // The question to show; empty when there is none any more.
  void promptChanged(const QString& prompt);

 private:
  void setPrompt(const QString& prompt);

  kapfix::v1::Mode mode_ = kapfix::v1::MODE_UNSPECIFIED;
  std::function<void()> pending_;
  QString prompt_;
  QShortcut* enter_;
  QShortcut* keypad_enter_;
  QShortcut* escape_;
  QTimer expiry_;
};

}  // namespace kapfix::station
