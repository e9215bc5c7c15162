#include "groundstation/status/lock_monitor.hpp"

#include <QApplication>
#include <QSettings>

namespace kapfix::station {
namespace {

const QString kAudibleKey = QStringLiteral("lock/audible_alert");

}  // namespace

LockMonitor::LockMonitor(AgentClient& client, LockQualityOptions options, QObject* parent)
    : QObject(parent), quality_(options) {
  audible_ = QSettings().value(kAudibleKey, false).toBool();
  stale_ = !client.linkState().up;
  connect(&client, &AgentClient::telemetryReceived, this, &LockMonitor::add);
  connect(&client, &AgentClient::linkChanged, this, [this](const LinkState& state) {
    if (stale_ == !state.up) return;
    stale_ = !state.up;
    emit changed();
  });
}

void LockMonitor::setAudible(bool audible) {
  audible_ = audible;
  QSettings().setValue(kAudibleKey, audible);
}

void LockMonitor::reset() {
  quality_.reset();
  emit changed();
}

void LockMonitor::add(const kapfix::v1::Telemetry& telemetry) {
  const LockVerdict before = quality_.reading().verdict;
  const LockVerdict now = quality_.add(telemetry).verdict;
  if (now == LockVerdict::kLost && before != LockVerdict::kLost) {
    ++alerts_;
    if (audible_) QApplication::beep();
  }
  // Telemetry arriving proves the link, whatever the last link poll said.
  stale_ = false;
  emit changed();
}

}  // namespace kapfix::station
