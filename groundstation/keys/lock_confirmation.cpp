#include "groundstation/keys/lock_confirmation.hpp"

#include <QWidget>
#include <utility>

namespace kapfix::station {
namespace {

bool HoldsALock(kapfix::v1::Mode mode) {
  return mode == kapfix::v1::MODE_FIXATE || mode == kapfix::v1::MODE_FOLLOW;
}

}  // namespace

LockConfirmation::LockConfirmation(AgentClient& client, QWidget& window, QObject* parent)
    : QObject(parent),
      enter_(new QShortcut(QKeySequence(Qt::Key_Return), &window)),
      keypad_enter_(new QShortcut(QKeySequence(Qt::Key_Enter), &window)),
      escape_(new QShortcut(QKeySequence(Qt::Key_Escape), &window)) {
  for (QShortcut* shortcut : {enter_, keypad_enter_, escape_}) shortcut->setEnabled(false);
  connect(enter_, &QShortcut::activated, this, &LockConfirmation::confirm);
  connect(keypad_enter_, &QShortcut::activated, this, &LockConfirmation::confirm);
  connect(escape_, &QShortcut::activated, this, &LockConfirmation::cancel);
  expiry_.setSingleShot(true);
  expiry_.setInterval(kExpiryMs);
  connect(&expiry_, &QTimer::timeout, this, &LockConfirmation::cancel);
  connect(&client, &AgentClient::telemetryReceived, this,
          [this](const kapfix::v1::Telemetry& telemetry) { mode_ = telemetry.mode(); });
  connect(&client, &AgentClient::stateReceived, this,
          [this](const kapfix::v1::AgentState& state) { mode_ = state.mode(); });
}

void LockConfirmation::request(const QString& what, std::function<void()> action) {
  if (!HoldsALock(mode_)) {
    cancel();
    action();
    return;
  }
  pending_ = std::move(action);
  setPrompt(tr("Press Enter to %1: the present lock will be dropped. Esc cancels.").arg(what));
  for (QShortcut* shortcut : {enter_, keypad_enter_, escape_}) shortcut->setEnabled(true);
  expiry_.start();
}

void LockConfirmation::confirm() {
  if (!pending_) return;
  const std::function<void()> action = std::exchange(pending_, nullptr);
  cancel();
  action();
}

void LockConfirmation::cancel() {
  pending_ = nullptr;
  expiry_.stop();
  for (QShortcut* shortcut : {enter_, keypad_enter_, escape_}) shortcut->setEnabled(false);
  setPrompt(QString());
}

void LockConfirmation::setPrompt(const QString& prompt) {
  if (prompt == prompt_) return;
  prompt_ = prompt;
  emit promptChanged(prompt_);
}

}  // namespace kapfix::station
