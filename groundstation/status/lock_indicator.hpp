#pragma once

// LOCKED / DEGRADED / LOST in large type, with the residual and its RMS [px], read at arm's
// length in sunlight: white on a saturated colour, the words carry the meaning (not only the
// colour). Greyed when the link is down (the value is the last one heard). Two sizes: one
// over the video, one in the status bar.

#include <QLabel>

#include "groundstation/status/lock_monitor.hpp"

namespace kapfix::station {

class LockIndicator final : public QLabel {
  Q_OBJECT

 public:
  enum class Size { kStatusBar, kOnVideo };

  LockIndicator(const LockMonitor& monitor, Size size, QWidget* parent = nullptr);

  // The verdict word shown ("LOCKED", "DEGRADED", "LOST", "NO LOCK", ...).
  QString verdictText() const { return verdict_text_; }

 private:
  void showReading();

  const LockMonitor& monitor_;
  Size size_;
  QString verdict_text_;
};

}  // namespace kapfix::station
