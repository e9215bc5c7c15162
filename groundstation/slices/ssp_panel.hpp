#pragma once

// The Slice Selection Process, for the operator (SPEC §2.6, issue 4): start it with a
// deadline and follow its progress; read every slice's DC, DC with hysteresis, FFT score and
// single-shot score in a table and its displacement graph in a small multiple; the
// recommended slice is highlighted. The operator confirms it, or picks another one in the
// table (double-click, or select and "Use selected"), on a small multiple, or on the video.

#include <QAction>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QWidget>

#include "groundstation/client/agent_client.hpp"

namespace kapfix::station {

class LockConfirmation;
class SliceGraphGrid;

class SspPanel final : public QWidget {
  Q_OBJECT

 public:
  enum Column { kSlice, kDc, kDcHysteresis, kFft, kSingleShot, kRank, kColumnCount };

  explicit SspPanel(AgentClient& client, QWidget* parent = nullptr);

  QAction* runAction() const { return run_; }
  QAction* confirmAction() const { return confirm_; }
  QTableWidget& table() const { return *table_; }
  SliceGraphGrid& graphs() const { return *graphs_; }
  QProgressBar& progress() const { return *progress_; }
  QString messageText() const { return message_->text(); }
  unsigned recommended() const { return recommended_; }

  // Sends select_slice `index` and reports the outcome in the panel.
  void pickSlice(unsigned index);
  // Starting SSP while the agent holds a lock asks this first (optional).
  void setConfirmation(LockConfirmation* confirmation) { confirmation_ = confirmation; }
  // A new session: the old agent's results, slice in use and messages go.
  void clearSession();

 private:
  void setUpTable();       // columns, sizes and tooltip of the slice table
  void connectControls();  // the actions, the table, the graphs and the link
  void runSsp();
  void showReport(const kapfix::v1::SliceReport& report);
  void markInUse(unsigned slice);
  unsigned sliceOfRow(int row) const;  // [1..N] the slice a table row shows

  AgentClient& client_;
  QAction* run_;
  QAction* confirm_;
  QSpinBox* deadline_;
  QProgressBar* progress_;
  QTableWidget* table_;
  SliceGraphGrid* graphs_;
  QPushButton* use_selected_;
  QLabel* message_;
  unsigned recommended_ = 0;
  unsigned in_use_ = 0;
  LockConfirmation* confirmation_ = nullptr;
};

}  // namespace kapfix::station
