#pragma once

// One operator setting (a `kapfix-ctl set` key, link/setting_key.hpp): its editor and,
// next to it, what became of the last change — pending, accepted, or the agent's reason for
// refusing it. The row speaks in text values, the same the command line uses, so that one
// parser (MakeSetCommand) turns every change into its command.
//
// A number's limits are shown under its editor and checked by the row itself (issue 14,
// problem 8): the editor takes any number typed, so that nothing is silently clamped or
// reverted; a value out of the range is marked (red border, a message in plain words) and
// not sent, and the mark goes as soon as the value is fixed.

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
    double minimum = 0;  // kReal / kInteger: the schema's range (the agent checks too)
    double maximum = 1;
    bool zero_means_off = false;  // 0 is accepted too, meaning off
    QString unit;                 // of the range, as the schema writes it ("1": none)
    QString help;                 // what the setting does, in plain words
    int decimals = 2;             // kReal
    double step = 0.1;            // kReal / kInteger
    QStringList choices;          // kChoice: setting values, shown as they are
  };

  SettingRow(const Spec& spec, const QString& help, QWidget* parent = nullptr);

  const QString& key() const { return key_; }
  QWidget* editor() const { return editor_; }
  QLabel* statusLabel() const { return status_; }
  // The limits under the editor, e.g. "0 to 48 dB".
  QLabel* hintLabel() const { return hint_; }
  // The editor holds a value out of the range (marked, not sent).
  bool refusedLocally() const { return out_of_range_; }

  // The editor's value as setting text ("0.8", "h23", "on").
  QString value() const;
  // Shows the agent's value without sending anything; ignored while a change is pending.
  void showAgentValue(const QString& value);
  // Puts the operator's own `value` back in the editor (clearing any mark), without sending.
  void restoreOperatorValue(const QString& value);

  void markPending();
  void markAccepted();
  void markRefused(const QString& reason);

 signals:
  // The operator changed the value (not showAgentValue()).
  void edited(const QString& key, const QString& value);

 private:
  void setEditorValue(const QString& value);
  // Sends a number in range; marks one out of it.
  void numberEdited(double number);
  void markOutOfRange(bool out);
  bool inRange(double value) const;

  QString key_;
  Kind kind_;
  double minimum_;
  double maximum_;
  bool zero_means_off_;
  QString range_words_;  // "0 (off) or 0.1 to 60 fps"
  QString help_;
  QWidget* editor_ = nullptr;
  QLabel* status_;
  QLabel* hint_;
  bool pending_ = false;
  bool out_of_range_ = false;
  bool refused_ = false;  // the agent refused the value in the editor
};

}  // namespace kapfix::station
