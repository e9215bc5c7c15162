#include "groundstation/status/lock_indicator.hpp"

namespace kapfix::station {
namespace {

struct Look {
  QString word;
  QString background;
};

Look LookOf(LockVerdict verdict) {
  switch (verdict) {
    case LockVerdict::kLocked:
      return {QObject::tr("LOCKED"), QStringLiteral("#1e7b34")};
    case LockVerdict::kDegraded:
      return {QObject::tr("DEGRADED"), QStringLiteral("#b35c00")};
    case LockVerdict::kLost:
      return {QObject::tr("LOST"), QStringLiteral("#b3261e")};
    case LockVerdict::kNone:
      break;
  }
  return {QObject::tr("NO LOCK"), QStringLiteral("#5f6368")};
}

}  // namespace

LockIndicator::LockIndicator(const LockMonitor& monitor, Size size, QWidget* parent)
    : QLabel(parent), monitor_(monitor), size_(size) {
  setObjectName(size == Size::kOnVideo ? QStringLiteral("lockOnVideo")
                                       : QStringLiteral("lockInStatusBar"));
  setTextFormat(Qt::PlainText);
  setToolTip(
      tr("Lock quality from the agent's lock state, its confidence and the residual's "
         "RMS over 5 s. Residual: the displacement the servos have not taken out [px]"));
  QFont big = font();
  big.setBold(true);
  big.setPointSizeF(big.pointSizeF() * (size == Size::kOnVideo ? 1.6 : 1.2));
  setFont(big);
  setMargin(size == Size::kOnVideo ? 8 : 3);
  connect(&monitor_, &LockMonitor::changed, this, &LockIndicator::showReading);
  showReading();
}

void LockIndicator::showReading() {
  const LockReading& reading = monitor_.reading();
  Look look = LookOf(reading.verdict);
  // The agent's own word that it trails the view (a right match, but not held) says more
  // than "degraded".
  if (reading.off_target && reading.verdict == LockVerdict::kDegraded) {
    look.word = tr("OFF TARGET");
  }
  verdict_text_ = look.word;
  QString text = look.word;
  if (reading.verdict != LockVerdict::kNone) {
    text += size_ == Size::kOnVideo ? QStringLiteral("\n") : QStringLiteral("  ");
    text +=
        tr("%1 px · RMS %2 px").arg(reading.residual_px, 0, 'f', 1).arg(reading.rms_px, 0, 'f', 1);
    // The online calibration in the status bar only: the video's label stays short.
    if (size_ == Size::kStatusBar && !reading.calibration.empty()) {
      text += QStringLiteral("  ") + QString::fromStdString(reading.calibration);
    }
  }
  if (monitor_.stale()) {
    // The last value heard, not the present one: grey, and said in words.
    look.background = QStringLiteral("#9aa0a6");
    text += tr("  (no link)");
  }
  setText(text);
  setStyleSheet(QStringLiteral("QLabel { color: white; background: %1; border-radius: 6px; }")
                    .arg(look.background));
  // Over the video it is hidden while there is nothing to judge: the picture matters more.
  if (size_ == Size::kOnVideo) setVisible(reading.verdict != LockVerdict::kNone);
  adjustSize();
}

}  // namespace kapfix::station
