#include "groundstation/slices/ssp_panel.hpp"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QPointer>
#include <QSettings>
#include <QToolButton>
#include <QVBoxLayout>

#include "groundstation/keys/lock_confirmation.hpp"
#include "groundstation/slices/slice_graph_grid.hpp"

namespace kapfix::station {
namespace {

QTableWidgetItem* Cell(const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(Qt::ItemIsSelectable | Qt::ItemIsEnabled);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  return item;
}

}  // namespace

SspPanel::SspPanel(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      client_(client),
      run_(new QAction(tr("Run SSP"), this)),
      confirm_(new QAction(tr("Confirm recommended"), this)),
      deadline_(new QSpinBox(this)),
      progress_(new QProgressBar(this)),
      table_(new QTableWidget(0, kColumnCount, this)),
      graphs_(new SliceGraphGrid(this)),
      use_selected_(new QPushButton(tr("Use selected slice"), this)),
      message_(new QLabel(this)) {
  run_->setShortcut(QKeySequence(Qt::Key_F5));
  run_->setToolTip(tr("Start the Slice Selection Process on a free swing (F5)"));
  confirm_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Return));
  confirm_->setToolTip(tr("Fixate on the recommended slice (Ctrl+Enter)"));
  confirm_->setEnabled(false);

  deadline_->setRange(20, 5000);
  deadline_->setSuffix(tr(" frames"));
  deadline_->setToolTip(tr("Deadline: SSP stops with what it has after this many frames"));
  deadline_->setValue(QSettings().value(QStringLiteral("ssp/deadline_frames"), 400).toInt());
  connect(deadline_, &QSpinBox::valueChanged, this,
          [](int frames) { QSettings().setValue(QStringLiteral("ssp/deadline_frames"), frames); });
  progress_->setRange(0, 1);
  progress_->setValue(0);
  progress_->setFormat(tr("%v / %m frames"));

  auto* run_button = new QToolButton(this);
  run_button->setDefaultAction(run_);
  run_button->setToolButtonStyle(Qt::ToolButtonTextOnly);
  auto* confirm_button = new QToolButton(this);
  confirm_button->setDefaultAction(confirm_);
  auto* top = new QHBoxLayout;
  top->addWidget(run_button);
  top->addWidget(deadline_);
  top->addWidget(progress_, 1);

  setUpTable();

  auto* buttons = new QHBoxLayout;
  buttons->addWidget(confirm_button);
  buttons->addWidget(use_selected_);
  buttons->addStretch(1);
  use_selected_->setEnabled(false);
  message_->setObjectName(QStringLiteral("sspMessage"));
  message_->setWordWrap(true);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top);
  layout->addWidget(table_);
  layout->addLayout(buttons);
  layout->addWidget(message_);
  layout->addWidget(graphs_, 1);

  connectControls();
}

void SspPanel::setUpTable() {
  table_->setObjectName(QStringLiteral("sliceTable"));
  table_->setHorizontalHeaderLabels(
      {tr("Slice"), tr("DC"), tr("DC hyst."), tr("FFT /1000"), tr("1-shot"), tr("Rank")});
  table_->verticalHeader()->hide();
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  // Each column as wide as its header and numbers (never truncated); a narrow dock scrolls.
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->verticalHeader()->setDefaultSectionSize(table_->fontMetrics().height() + 6);
  // Room for the thesis's nine slices and the header, no more: the graphs get the rest.
  table_->setMinimumHeight(11 * (table_->fontMetrics().height() + 6));
  table_->setMaximumHeight(11 * (table_->fontMetrics().height() + 6));
  table_->setToolTip(tr("Double-click a slice to fixate on it"));
}

void SspPanel::connectControls() {
  connect(run_, &QAction::triggered, this, [this] {
    if (confirmation_ == nullptr) {
      runSsp();
    } else {
      confirmation_->request(tr("start SSP"), [this] { runSsp(); });
    }
  });
  connect(confirm_, &QAction::triggered, this, [this] {
    if (recommended_ > 0) pickSlice(recommended_);
  });
  connect(use_selected_, &QPushButton::clicked, this, [this] {
    const auto rows = table_->selectionModel()->selectedRows();
    if (!rows.isEmpty()) pickSlice(sliceOfRow(rows.front().row()));
  });
  connect(table_, &QTableWidget::itemSelectionChanged, this,
          [this] { use_selected_->setEnabled(!table_->selectedItems().isEmpty()); });
  connect(table_, &QTableWidget::cellDoubleClicked, this,
          [this](int row, int /*column*/) { pickSlice(sliceOfRow(row)); });
  connect(graphs_, &SliceGraphGrid::sliceClicked, this, &SspPanel::pickSlice);

  connect(&client_, &AgentClient::sliceReportReceived, this, &SspPanel::showReport);
  connect(&client_, &AgentClient::stateReceived, this, [this](const kapfix::v1::AgentState& state) {
    if (state.has_last_slice_report() && recommended_ == 0) showReport(state.last_slice_report());
    markInUse(state.slice());
  });
  connect(&client_, &AgentClient::telemetryReceived, this,
          [this](const kapfix::v1::Telemetry& telemetry) { markInUse(telemetry.slice()); });
}

void SspPanel::runSsp() {
  kapfix::v1::Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  command.mutable_set_mode()->set_deadline_frames(static_cast<std::uint32_t>(deadline_->value()));
  progress_->setRange(0, deadline_->value());
  progress_->setValue(0);
  message_->setText(tr("Starting SSP …"));
  client_.sendCommand(std::move(command), [self = QPointer(this)](const CommandOutcome& outcome) {
    if (self.isNull()) return;
    self->message_->setText(outcome.ok ? tr("SSP running: let the platform swing freely")
                                       : tr("SSP refused: %1").arg(outcome.reason));
  });
}

void SspPanel::pickSlice(unsigned index) {
  if (index == 0) return;
  kapfix::v1::Command command;
  command.set_select_slice(index);
  message_->setText(tr("Selecting slice %1 …").arg(index));
  client_.sendCommand(
      std::move(command), [self = QPointer(this), index](const CommandOutcome& outcome) {
        if (self.isNull()) return;
        if (outcome.ok) {
          self->message_->setText(tr("Fixating on slice %1").arg(index));
          self->markInUse(index);
        } else {
          self->message_->setText(tr("Slice %1 refused: %2").arg(index).arg(outcome.reason));
        }
      });
}

void SspPanel::showReport(const kapfix::v1::SliceReport& report) {
  progress_->setRange(0, static_cast<int>(std::max<std::uint32_t>(1, report.progress_total())));
  progress_->setValue(static_cast<int>(report.progress_done()));
  if (!report.finished()) {
    message_->setText(
        tr("SSP: %1 of %2 frames").arg(report.progress_done()).arg(report.progress_total()));
    if (report.slices_size() == 0) return;
  }
  recommended_ = report.recommended_slice();
  confirm_->setEnabled(report.finished() && recommended_ > 0);
  confirm_->setText(recommended_ > 0 ? tr("Confirm slice %1").arg(recommended_)
                                     : tr("Confirm recommended"));
  table_->setRowCount(report.slices_size());
  for (int row = 0; row < report.slices_size(); ++row) {
    const auto& slice = report.slices(row);
    QTableWidgetItem* index = Cell(QString::number(slice.index()));
    index->setData(Qt::UserRole, slice.index());  // the text also marks the slice in use
    table_->setItem(row, kSlice, index);
    table_->setItem(row, kDc, Cell(QString::number(slice.dc())));
    table_->setItem(row, kDcHysteresis, Cell(QString::number(slice.dc_hysteresis())));
    table_->setItem(row, kFft, Cell(QString::number(slice.fft() / 1000.0, 'f', 2)));
    table_->setItem(row, kSingleShot,
                    Cell(QString::number(static_cast<double>(slice.single_shot()), 'f', 2)));
    table_->setItem(row, kRank,
                    Cell(slice.rank() > 0 ? QString::number(slice.rank()) : QStringLiteral("—")));
  }
  markInUse(in_use_);
  graphs_->showReport(report);
  if (report.finished()) {
    message_->setText(recommended_ > 0
                          ? tr("SSP finished%1: slice %2 recommended. Confirm it, or pick another.")
                                .arg(report.deadline_reached() ? tr(" (deadline)") : QString())
                                .arg(recommended_)
                          : tr("SSP finished without a recommendation"));
  }
}

void SspPanel::clearSession() {
  recommended_ = 0;
  in_use_ = 0;
  table_->setRowCount(0);
  graphs_->showReport(kapfix::v1::SliceReport());
  confirm_->setEnabled(false);
  confirm_->setText(tr("Confirm recommended"));
  use_selected_->setEnabled(false);
  progress_->setRange(0, 1);
  progress_->setValue(0);
  message_->clear();
}

unsigned SspPanel::sliceOfRow(int row) const {
  const QTableWidgetItem* item = table_->item(row, kSlice);
  return item == nullptr ? 0 : item->data(Qt::UserRole).toUInt();
}

void SspPanel::markInUse(unsigned slice) {
  in_use_ = slice;
  for (int row = 0; row < table_->rowCount(); ++row) {
    const unsigned index = sliceOfRow(row);
    const bool best = index == recommended_;
    for (int column = 0; column < kColumnCount; ++column) {
      QTableWidgetItem* item = table_->item(row, column);
      QFont font = item->font();
      font.setBold(best);
      item->setFont(font);
      item->setBackground(best ? QColor(200, 235, 207) : QColor(Qt::transparent));
    }
    table_->item(row, kSlice)->setText(QString::number(index));
    table_->item(row, kSlice)->setToolTip(best ? tr("Recommended") : QString());
    if (index == in_use_) {
      table_->item(row, kSlice)->setText(QString::number(index) + QStringLiteral(" ●"));
      table_->item(row, kSlice)->setToolTip(tr("In use"));
    }
  }
}

}  // namespace kapfix::station
