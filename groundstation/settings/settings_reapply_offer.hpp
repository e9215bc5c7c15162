#pragma once

// After an agent restart (issue 14): when the new agent's settings differ from those this
// station's operator set in this run, a full-width line lists the differing keys with both
// values and offers one button to send the operator's values again. Never automatic: the
// agent may have been restarted on purpose with other settings. Armed by a restart; it
// follows every state until the operator re-applies or dismisses, and hides itself when
// nothing differs (or no longer differs).

#include <QLabel>
#include <QPushButton>
#include <QStringList>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class SettingsPanel;

class SettingsReapplyOffer final : public QWidget {
  Q_OBJECT

 public:
  SettingsReapplyOffer(AgentClient& client, SettingsPanel& settings, QWidget* parent = nullptr);

  // A restarted agent: compare its next states with the operator's settings.
  void arm();

  QString text() const { return label_->text(); }
  // The keys on offer (empty while hidden).
  const QStringList& keys() const { return keys_; }
  QPushButton& reapplyButton() const { return *reapply_; }
  QPushButton& dismissButton() const { return *dismiss_; }

 private:
  void compare(const kapfix::v1::AgentState& state);
  void disarm();

  SettingsPanel& settings_;
  QLabel* label_;
  QPushButton* reapply_;
  QPushButton* dismiss_;
  bool armed_ = false;
  QStringList keys_;
};

}  // namespace kapfix::station
