#pragma once

// One operator setting (a `kapfix-ctl set` key, tools/ctl/setting_key.hpp): its editor and,
// next to it, what became of the last change — pending, accepted, or the agent's reason for
// refusing it. The row speaks in text values, the same the command line uses, so that one
// parser (MakeSetCommand) turns every change into its command.

#include <QLabel>
#include <QString>
#include <QStringList>
#include <QWidget>

namespace kapfix::station {

class SettingRow final : public QWidget {
  Q_OBJECT

 public:
  enum class Kind { kReal, kInteger, kChoice, kSwitch, kText };

  struct Spec {
    QString key;    // setting key, e.g. "p"
    QString label;  // what the operator reads, with its unit
    Kind kind = Kind::kReal;
    double minimum = 0;  // kReal / kInteger: editor range, the schema's (the agent checks too)
    double maximum = 1;
    int decimals = 2;     // kReal
    double step = 0.1;    // kReal / kInteger
    QStringList choices;  // kChoice: setting values, shown as they are
  };

  SettingRow(const Spec& spec, const QString& help, QWidget* parent = nullptr);

  const QString& key() const { return key_; }
  QWidget* editor() const { return editor_; }
  QLabel* statusLabel() const { return status_; }

  // The editor's value as setting text ("0.8", "h23", "on").
  QString value() const;
  // Shows the agent's value without sending anything; ignored while a change is pending.
  void showAgentValue(const QString& value);

  void markPending();
  void markAccepted();
  void markRefused(const QString& reason);

 signals:
  // The operator changed the value (not showAgentValue()).
  void edited(const QString& key, const QString& value);

 private:
  void setEditorValue(const QString& value);

  QString key_;
  Kind kind_;
  QWidget* editor_ = nullptr;
  QLabel* status_;
  bool pending_ = false;
};

}  // namespace kapfix::station
