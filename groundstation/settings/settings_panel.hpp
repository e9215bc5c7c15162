#pragma once

// The agent's settings (issue 4): controller gains, search, camera, video and lens with its
// calibration. Every change is sent at once as its own command; the row shows whether the
// agent took it, or its reason for refusing. The agent's state (on connect and after every
// change) fills the editors, so the panel shows what the agent really uses.

#include <QMap>
#include <QStringList>
#include <QWidget>
#include <vector>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class CalibrationView;
class SettingRow;

class SettingsPanel final : public QWidget {
  Q_OBJECT

 public:
  explicit SettingsPanel(AgentClient& client, QWidget* parent = nullptr);

  // The row of a setting key ("p", "strategy", ...); nullptr for an unknown key.
  SettingRow* row(const QString& key) const { return rows_.value(key, nullptr); }
  CalibrationView& calibration() const { return *calibration_; }

  // A setting where the agent's value differs from the one this station's operator last set
  // (and the agent accepted) in this run.
  struct Difference {
    QString key;
    QString agent_value;
    QString operator_value;
  };
  std::vector<Difference> differencesFrom(const kapfix::v1::AgentState& state) const;
  // Sends the operator's last value of each key again, as if typed.
  void reapply(const QStringList& keys);

 private:
  void send(const QString& key, const QString& value);
  void showState(const kapfix::v1::AgentState& state);

  AgentClient& client_;
  QMap<QString, SettingRow*> rows_;
  QMap<QString, QString> operator_values_;  // key → last value sent and accepted
  CalibrationView* calibration_;
};

}  // namespace kapfix::station
