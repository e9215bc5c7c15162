#pragma once

// Keys that keep their window-wide meaning even while a text or number field has the focus
// (issue 14: Space must take the photo, not erase the focused number). Qt first offers a key
// to the focused widget (ShortcutOverride), and editors claim printable keys; this filter
// answers that offer for them, so the window's shortcut runs and the editor keeps its value.

#include <QKeySequence>
#include <QList>
#include <QObject>

class QWidget;

namespace kapfix::station {

class PriorityKeys final : public QObject {
  Q_OBJECT

 public:
  // For every widget inside `window`; installed on the application while this lives.
  PriorityKeys(QWidget& window, QList<QKeySequence> keys, QObject* parent = nullptr);
  ~PriorityKeys() override;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  QWidget& window_;
  QList<QKeySequence> keys_;
};

}  // namespace kapfix::station
