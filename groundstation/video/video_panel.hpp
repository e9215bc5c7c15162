#pragma once

// The centre of the window: the live video, a row of overlay switches (remembered between
// runs), and picking a slice by clicking on the picture (sent as select_slice).

#include <QCheckBox>
#include <QGridLayout>
#include <QLabel>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/video/video_view.hpp"

namespace kapfix::station {

class LockConfirmation;

class VideoPanel final : public QWidget {
  Q_OBJECT

 public:
  explicit VideoPanel(AgentClient& client, QWidget* parent = nullptr);

  VideoView& view() { return *view_; }
  // The switch of each overlay, by object name ("overlay_slice_grid", ...).
  QCheckBox* overlaySwitch(const QString& name) const;
  QString messageText() const { return message_->text(); }
  // Shown over the top-right corner of the picture (the lock indicator); not owned before.
  void setCornerWidget(QWidget* widget);
  // A click on the picture while the agent holds a lock asks this first (optional).
  void setConfirmation(LockConfirmation* confirmation) { confirmation_ = confirmation; }
  // A new session: the old agent's picture and messages go.
  void clearSession();

 private:
  void pickSlice(unsigned index);
  void sendSlice(unsigned index);
  void applySwitches();

  AgentClient& client_;
  VideoView* view_;
  QLabel* message_;
  LockConfirmation* confirmation_ = nullptr;
  QGridLayout* picture_layout_;
};

}  // namespace kapfix::station
