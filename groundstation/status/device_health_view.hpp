#pragma once

// The devices in the status bar (issue 14): the camera and the servo controller, each OK,
// WAITING (not there since the start, retried) or LOST (was working, failed; the servos hold),
// with the agent's reason. LOST is unmissable: white on red, bold, in capitals. From the
// agent's state and from every telemetry frame (whichever is newer).

#include <QLabel>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class DeviceHealthView final : public QWidget {
  Q_OBJECT

 public:
  // Characters of the agent's reason shown in the bar; the whole reason is the tooltip.
  static constexpr int kReasonShownChars = 60;

  explicit DeviceHealthView(AgentClient& client, QWidget* parent = nullptr);

  QString cameraText() const { return camera_->text(); }
  QString servoText() const { return servos_->text(); }
  // Either device is LOST.
  bool anyLost() const { return camera_lost_ || servos_lost_; }

 private:
  // Shows `health` of the device `name` ("Camera") on `label`; returns whether it is LOST.
  static bool show(QLabel& label, const QString& name, const kapfix::v1::DeviceHealth& health);

  QLabel* camera_;
  QLabel* servos_;
  bool camera_lost_ = false;
  bool servos_lost_ = false;
};

}  // namespace kapfix::station
