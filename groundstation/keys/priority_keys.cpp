#include "groundstation/keys/priority_keys.hpp"

#include <QApplication>
#include <QKeyEvent>
#include <QWidget>

namespace kapfix::station {

PriorityKeys::PriorityKeys(QWidget& window, QList<QKeySequence> keys, QObject* parent)
    : QObject(parent), window_(window), keys_(std::move(keys)) {
  qApp->installEventFilter(this);
}

PriorityKeys::~PriorityKeys() { qApp->removeEventFilter(this); }

bool PriorityKeys::eventFilter(QObject* watched, QEvent* event) {
  if (event->type() != QEvent::ShortcutOverride) return false;
  auto* widget = qobject_cast<QWidget*>(watched);
  if (widget == nullptr || widget->window() != &window_) return false;
  const auto* key = static_cast<QKeyEvent*>(event);
  const QKeySequence pressed(key->keyCombination());
  if (!keys_.contains(pressed)) return false;
  // Not accepted: no editor claims it, so the shortcut map runs the window's action.
  event->ignore();
  return true;
}

}  // namespace kapfix::station
