#include "groundstation/events/event_log.hpp"

#include <QTime>

#include "groundstation/status/mode_name.hpp"
#include "tools/ctl/message_text.hpp"

namespace kapfix::station {
namespace {

QString CommandText(const kapfix::v1::Command& command) {
  switch (command.command_case()) {
    case kapfix::v1::Command::kSetMode:
      return QObject::tr("mode → %1").arg(ModeName(command.set_mode().mode()));
    case kapfix::v1::Command::kSelectSlice:
      return QObject::tr("select slice %1").arg(command.select_slice());
    case kapfix::v1::Command::kTakePhoto:
      return QObject::tr("take photo");
    case kapfix::v1::Command::kSetPhotoIntervalS:
      return QObject::tr("photo every %1 s")
          .arg(static_cast<double>(command.set_photo_interval_s()));
    case kapfix::v1::Command::kRequestState:
      return QObject::tr("request state");
    default: {
      // Settings: the changed fields, as protobuf prints them on one line.
      std::string text = command.ShortDebugString();
      return QObject::tr("set %1").arg(QString::fromStdString(text));
    }
  }
}

}  // namespace

EventLog::EventLog(AgentClient& client, QWidget* parent) : QPlainTextEdit(parent) {
  setObjectName(QStringLiteral("eventLog"));
  setReadOnly(true);
  setMaximumBlockCount(kMaxLines);
  setLineWrapMode(QPlainTextEdit::WidgetWidth);

  connect(&client, &AgentClient::linkChanged, this, [this](const LinkState& state) {
    if (state.replay) {
      addLine(state.up ? tr("replaying %1").arg(state.source) : tr("replay finished"),
              QColor(31, 95, 191));
    } else {
      addLine(state.up ? tr("link up: %1").arg(state.source) : tr("link down"),
              state.up ? QColor(30, 123, 52) : QColor(179, 38, 30));
    }
  });
  connect(&client, &AgentClient::commandSent, this, [this](const kapfix::v1::Command& command) {
    if (command.has_request_state()) return;  // routine, after each reconnection
    addLine(QStringLiteral("→ ") + CommandText(command));
  });
  connect(&client, &AgentClient::replyReceived, this, [this](const kapfix::v1::Reply& reply) {
    if (!reply.ok()) {
      addLine(tr("✗ refused: %1").arg(QString::fromStdString(reply.reason())), QColor(179, 38, 30));
    }
  });
  connect(&client, &AgentClient::sliceReportReceived, this,
          [this](const kapfix::v1::SliceReport& report) {
            if (report.finished()) {
              addLine(QString::fromStdString(kapfix::ctl::SliceReportText(report)));
            }
          });
  connect(&client, &AgentClient::calibrationReceived, this,
          [this](const kapfix::v1::CalibrationReport& report) {
            if (report.finished()) addLine(tr("calibration finished"));
          });
  connect(&client, &AgentClient::logReceived, this, [this](const kapfix::v1::Log& line) {
    if (line.level() < kapfix::v1::LOG_LEVEL_INFO) return;
    const QColor colour = line.level() >= kapfix::v1::LOG_LEVEL_ERROR  ? QColor(179, 38, 30)
                          : line.level() >= kapfix::v1::LOG_LEVEL_WARN ? QColor(176, 96, 0)
                                                                       : QColor();
    addLine(QStringLiteral("[%1] %2").arg(QString::fromStdString(line.logger()),
                                          QString::fromStdString(line.text())),
            colour);
  });
}

void EventLog::addLine(const QString& text, const QColor& colour) {
  const QString stamp = QTime::currentTime().toString(QStringLiteral("HH:mm:ss"));
  const QString line = stamp + QStringLiteral("  ") + text.toHtmlEscaped();
  appendHtml(colour.isValid()
                 ? QStringLiteral("<span style=\"color:%1\">%2</span>").arg(colour.name(), line)
                 : line);
}

}  // namespace kapfix::station
