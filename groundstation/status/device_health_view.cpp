#include "groundstation/status/device_health_view.hpp"

#include <QHBoxLayout>

namespace kapfix::station {

DeviceHealthView::DeviceHealthView(AgentClient& client, QWidget* parent)
    : QWidget(parent), camera_(new QLabel(this)), servos_(new QLabel(this)) {
  setObjectName(QStringLiteral("deviceHealth"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  for (QLabel* label : {camera_, servos_}) {
    label->setTextFormat(Qt::PlainText);
    label->setMargin(4);
    label->setVisible(false);  // until the agent reports it
    layout->addWidget(label);
  }
  const QString camera = tr("Camera");
  const QString servos = tr("Servos");
  connect(&client, &AgentClient::stateReceived, this,
          [this, camera, servos](const kapfix::v1::AgentState& state) {
            if (state.has_camera_health())
              camera_lost_ = show(*camera_, camera, state.camera_health());
            if (state.has_servo_health())
              servos_lost_ = show(*servos_, servos, state.servo_health());
          });
  connect(&client, &AgentClient::telemetryReceived, this,
          [this, camera, servos](const kapfix::v1::Telemetry& telemetry) {
            if (telemetry.has_camera_health()) {
              camera_lost_ = show(*camera_, camera, telemetry.camera_health());
            }
            if (telemetry.has_servo_health()) {
              servos_lost_ = show(*servos_, servos, telemetry.servo_health());
            }
          });
}

bool DeviceHealthView::show(QLabel& label, const QString& name,
                            const kapfix::v1::DeviceHealth& health) {
  const QString reason = QString::fromStdString(health.reason());
  QString shown = reason;
  if (shown.size() > kReasonShownChars) shown = shown.left(kReasonShownChars - 1) + QChar(0x2026);
  QString text;
  QString style;
  switch (health.status()) {
    case kapfix::v1::DEVICE_OK:
      text = tr("%1 OK").arg(name);
      style = QStringLiteral("QLabel { color: #1e7b34; }");
      break;
    case kapfix::v1::DEVICE_WAITING:
      text = tr("%1 WAITING").arg(name);
      style = QStringLiteral("QLabel { color: black; background: #f2c94c; border-radius: 4px; }");
      break;
    case kapfix::v1::DEVICE_LOST:
      text = tr("%1 LOST").arg(name.toUpper());
      style = QStringLiteral(
          "QLabel { color: white; background: #b3261e; font-weight: bold; border-radius: 4px; }");
      break;
    default:
      label.setVisible(false);  // an agent older than the field: nothing to say
      return false;
  }
  if (!shown.isEmpty()) text += QStringLiteral(": ") + shown;
  label.setText(text);
  label.setToolTip(reason.isEmpty() ? text : reason);
  label.setStyleSheet(style);
  label.setVisible(true);
  return health.status() == kapfix::v1::DEVICE_LOST;
}

}  // namespace kapfix::station
