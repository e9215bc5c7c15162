#include "groundstation/events/event_log.hpp"

#include <QTime>

#include "groundstation/status/mode_name.hpp"

namespace kapfix::station {
namespace {

const QColor kGood(30, 123, 52);
const QColor kBad(179, 38, 30);
const QColor kWarn(176, 96, 0);
const QColor kReplay(31, 95, 191);

bool HoldsASlice(kapfix::v1::Mode mode) {
  return mode == kapfix::v1::MODE_FIXATE || mode == kapfix::v1::MODE_FOLLOW;
}

}  // namespace

QString SspResultLine(const kapfix::v1::SliceReport& report) {
  const QString frames =
      QObject::tr("after %1 frames%2")
          .arg(report.progress_done())
          .arg(report.deadline_reached() ? QObject::tr(" (deadline)") : QString());
  for (const auto& slice : report.slices()) {
    if (slice.index() != report.recommended_slice()) continue;
    return QObject::tr("SSP finished: slice %1 recommended (DC %2, FFT %3 k) of %4 slices %5")
        .arg(slice.index())
        .arg(slice.dc())
        .arg(slice.fft() / 1000.0, 0, 'f', 2)
        .arg(report.slices_size())
        .arg(frames);
  }
  return QObject::tr("SSP finished without a recommendation %1").arg(frames);
}

EventLog::EventLog(AgentClient& client, QWidget* parent) : QPlainTextEdit(parent) {
  setObjectName(QStringLiteral("eventLog"));
  setReadOnly(true);
  setMaximumBlockCount(kMaxLines);
  setLineWrapMode(QPlainTextEdit::WidgetWidth);

  connect(&client, &AgentClient::linkChanged, this, &EventLog::showLink);
  connect(&client, &AgentClient::telemetryReceived, this,
          [this](const kapfix::v1::Telemetry& telemetry) {
            showMode(telemetry.mode(), telemetry.slice());
          });
  connect(&client, &AgentClient::stateReceived, this,
          [this](const kapfix::v1::AgentState& state) { showMode(state.mode(), state.slice()); });
  connect(&client, &AgentClient::replyReceived, this, [this](const kapfix::v1::Reply& reply) {
    if (!reply.ok()) addLine(tr("refused: %1").arg(QString::fromStdString(reply.reason())), kBad);
  });
  connect(&client, &AgentClient::photoChunkReceived, this, &EventLog::showPhoto);
  connect(&client, &AgentClient::sliceReportReceived, this,
          [this](const kapfix::v1::SliceReport& report) {
            if (report.finished()) addLine(SspResultLine(report));
          });
  connect(&client, &AgentClient::calibrationReceived, this,
          [this](const kapfix::v1::CalibrationReport& report) {
            if (report.finished()) addLine(tr("calibration finished"));
          });
  connect(&client, &AgentClient::logReceived, this, [this](const kapfix::v1::Log& line) {
    if (line.level() < kapfix::v1::LOG_LEVEL_WARN) return;
    addLine(QStringLiteral("[%1] %2").arg(QString::fromStdString(line.logger()),
                                          QString::fromStdString(line.text())),
            line.level() >= kapfix::v1::LOG_LEVEL_ERROR ? kBad : kWarn);
  });
}

void EventLog::showLink(const LinkState& state) {
  // The link state is re-announced for every latency change: only a change of up/down counts.
  if (link_known_ && state.up == link_up_ && state.replay == replay_) return;
  link_known_ = true;
  link_up_ = state.up;
  replay_ = state.replay;
  if (state.replay) {
    addLine(state.up ? tr("replaying %1").arg(state.source) : tr("replay finished"), kReplay);
  } else if (state.up) {
    addLine(tr("link up: %1").arg(state.source), kGood);
  } else if (!state.source.isEmpty()) {
    addLine(tr("link down"), kBad);
  }
}

void EventLog::showMode(kapfix::v1::Mode mode, unsigned slice) {
  const unsigned shown_slice = HoldsASlice(mode) ? slice : 0;
  if (mode == mode_ && shown_slice == slice_) return;
  mode_ = mode;
  slice_ = shown_slice;
  addLine(shown_slice > 0 ? tr("mode: %1 on slice %2").arg(ModeName(mode)).arg(shown_slice)
                          : tr("mode: %1").arg(ModeName(mode)));
}

void EventLog::showPhoto(const kapfix::v1::Photo& chunk) {
  // One line per photo, when its last chunk arrives.
  if (chunk.offset_bytes() + chunk.data().size() < chunk.total_bytes()) return;
  addLine(tr("photo %1 (slice %2, confidence %3)")
              .arg(QString::fromStdString(chunk.metadata().file_name()))
              .arg(chunk.metadata().slice())
              .arg(static_cast<double>(chunk.metadata().confidence()), 0, 'f', 2));
}

void EventLog::addLine(const QString& text, const QColor& colour) {
  const QString stamp = QTime::currentTime().toString(QStringLiteral("HH:mm:ss"));
  const QString line = stamp + QStringLiteral("  ") + text.toHtmlEscaped();
  appendHtml(colour.isValid()
                 ? QStringLiteral("<span style=\"color:%1\">%2</span>").arg(colour.name(), line)
                 : line);
}

QStringList EventLog::lines() const {
  QStringList result;
  for (const QString& line : toPlainText().split(QLatin1Char('\n'), Qt::SkipEmptyParts)) {
    result.append(line.section(QLatin1Char(' '), 1).trimmed());  // after "HH:mm:ss"
  }
  return result;
}

}  // namespace kapfix::station
