#include "groundstation/snapshot/ssp_screenshot.hpp"

#include <QCoreApplication>
#include <QPixmap>
#include <QWidget>
#include <cstdio>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/slices/ssp_panel.hpp"

namespace kapfix::station {
namespace {

constexpr int kFixateSettleMs = 6000;  // [ms] more than the lock indicator's RMS window

}  // namespace

SspScreenshot::SspScreenshot(QWidget& window, AgentClient& client, SspPanel& ssp,
                             SspScreenshotOptions options, QObject* parent)
    : QObject(parent), window_(window), options_(std::move(options)) {
  connect(&client, &AgentClient::sliceReportReceived, this,
          [this, &ssp](const kapfix::v1::SliceReport& report) {
            if (!report.finished() || scheduled_) return;
            scheduled_ = true;
            if (options_.fixate) {
              // After the report's own state settles, as an operator would confirm.
              QTimer::singleShot(500, this, [&ssp] { ssp.confirmAction()->trigger(); });
            }
            // Fixating: long enough for the 5 s RMS to leave the acquisition behind.
            QTimer::singleShot(
                options_.fixate ? options_.delay_ms + kFixateSettleMs : options_.delay_ms, this,
                &SspScreenshot::take);
          });
  if (options_.run_ssp) {
    auto start = [this, &ssp](const LinkState& state) {
      if (ssp_started_ || !state.up || state.replay) return;
      ssp_started_ = true;
      ssp.runAction()->trigger();
    };
    connect(&client, &AgentClient::linkChanged, this, start);
    start(client.linkState());
  }
  timeout_.setSingleShot(true);
  timeout_.setInterval(options_.timeout_ms);
  connect(&timeout_, &QTimer::timeout, this, &SspScreenshot::take);
  timeout_.start();
}

void SspScreenshot::take() {
  timeout_.stop();
  const bool saved = window_.grab().save(options_.path, "PNG");
  std::fprintf(stderr, "kapfix-station: %s %s\n", saved ? "saved" : "could not save",
               options_.path.toLocal8Bit().constData());
  QCoreApplication::exit(saved ? 0 : 1);
}

}  // namespace kapfix::station
