#pragma once

// The centre of the window: the live video, a row of overlay switches (remembered between
// runs), and picking a slice by clicking on the picture (sent as select_slice).

#include <QCheckBox>
#include <QLabel>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/video/video_view.hpp"

namespace kapfix::station {

class VideoPanel final : public QWidget {
  Q_OBJECT

 public:
  explicit VideoPanel(AgentClient& client, QWidget* parent = nullptr);

  VideoView& view() { return *view_; }
  // The switch of each overlay, by object name ("overlay_slice_grid", ...).
  QCheckBox* overlaySwitch(const QString& name) const;
  QString messageText() const { return message_->text(); }

 private:
  void pickSlice(unsigned index);
  void applySwitches();

  AgentClient& client_;
  VideoView* view_;
  QLabel* message_;
};

}  // namespace kapfix::station
