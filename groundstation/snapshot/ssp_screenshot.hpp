#pragma once

// For documentation and the README (issue 4): saves a picture of the window once SSP results
// are on screen — after the first finished SliceReport, plus a delay for the graphs to fill —
// then quits. Optionally starts SSP itself as soon as the link is up, so a script can take
// the picture against any agent: `kapfix-station --agent HOST --run-ssp --screenshot F`; with
// --fixate it confirms the recommended slice first, for a picture of the lock indicator.

#include <QObject>
#include <QString>
#include <QTimer>

namespace kapfix::station {

class AgentClient;
class SspPanel;

struct SspScreenshotOptions {
  QString path;            // PNG to write
  bool run_ssp = false;    // start SSP once the link is up
  bool fixate = false;     // confirm the recommended slice; the picture shows the fixation
  int delay_ms = 3000;     // [ms] after the finished report
  int timeout_ms = 60000;  // [ms] take the picture anyway after this long
};

class SspScreenshot final : public QObject {
  Q_OBJECT

 public:
  SspScreenshot(QWidget& window, AgentClient& client, SspPanel& ssp, SspScreenshotOptions options,
                QObject* parent = nullptr);

 private:
  void take();

  QWidget& window_;
  SspScreenshotOptions options_;
  bool ssp_started_ = false;
  bool scheduled_ = false;
  QTimer timeout_;
};

}  // namespace kapfix::station
