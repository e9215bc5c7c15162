#pragma once

// Stabilised photos (issue 4): capture now (Space), capture every N seconds (the agent's own
// timer, so it keeps going while the link is down), the folder they are saved in (kept
// between runs), and a gallery strip of what arrived. Every photo the agent publishes is
// saved — also those it resends after a link loss (LinkResync asks for them) — and listed
// with the quality the agent measured, sortable, blurred or off-target ones flagged.

#include <QAction>
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QSet>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"
#include "groundstation/photos/photo_store.hpp"

namespace kapfix::station {

class PhotoQualityTable;

class PhotosPanel final : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kThumbnailPx = 96;  // [px] gallery thumbnail height

  explicit PhotosPanel(AgentClient& client, QWidget* parent = nullptr);

  QAction* captureAction() const { return capture_; }
  QListWidget& gallery() const { return *gallery_; }
  PhotoQualityTable& quality() const { return *quality_; }
  QString folder() const { return store_.folder(); }
  void setFolder(const QString& folder);
  QString messageText() const { return message_->text(); }
  QCheckBox& intervalSwitch() const { return *interval_on_; }
  QDoubleSpinBox& intervalSeconds() const { return *interval_s_; }

 signals:
  void photoSaved(const kapfix::station::SavedPhoto& photo);

 private:
  void capture();
  void sendInterval();
  void receive(const kapfix::v1::Photo& chunk);
  void chooseFolder();

  AgentClient& client_;
  PhotoStore store_;
  QAction* capture_;
  QCheckBox* interval_on_;
  QDoubleSpinBox* interval_s_;
  QLineEdit* folder_edit_;
  QListWidget* gallery_;
  PhotoQualityTable* quality_;
  QLabel* message_;
  QSet<QString> shown_;  // file names already in the gallery
};

}  // namespace kapfix::station
