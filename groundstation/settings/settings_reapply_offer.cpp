#include "groundstation/settings/settings_reapply_offer.hpp"

#include <QHBoxLayout>

#include "groundstation/settings/settings_panel.hpp"

namespace kapfix::station {
namespace {

// The agent's float as the operator would type it: "0.60000002" → "0.6".
QString Shown(const QString& value) {
  bool number = false;
  const double x = value.toDouble(&number);
  return number ? QString::number(x, 'g', 6) : value;
}

}  // namespace

SettingsReapplyOffer::SettingsReapplyOffer(AgentClient& client, SettingsPanel& settings,
                                           QWidget* parent)
    : QWidget(parent),
      settings_(settings),
      label_(new QLabel(this)),
      reapply_(new QPushButton(tr("Re-apply my settings"), this)),
      dismiss_(new QPushButton(tr("Keep the agent's"), this)) {
  setObjectName(QStringLiteral("settingsReapplyOffer"));
  setAttribute(Qt::WA_StyledBackground);
  setStyleSheet(QStringLiteral("#settingsReapplyOffer { background: #fff4d6; }"));
  label_->setTextFormat(Qt::PlainText);
  label_->setWordWrap(true);
  QFont bold = label_->font();
  bold.setBold(true);
  label_->setFont(bold);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(8, 4, 8, 4);
  layout->addWidget(label_, 1);
  layout->addWidget(reapply_);
  layout->addWidget(dismiss_);
  reapply_->setToolTip(tr("Send the values this station set before the restart again"));
  dismiss_->setToolTip(tr("Leave the restarted agent's settings as they are"));
  connect(reapply_, &QPushButton::clicked, this, [this] {
    const QStringList keys = keys_;
    disarm();
    settings_.reapply(keys);
  });
  connect(dismiss_, &QPushButton::clicked, this, &SettingsReapplyOffer::disarm);
  connect(&client, &AgentClient::stateReceived, this, &SettingsReapplyOffer::compare);
  setVisible(false);
}

void SettingsReapplyOffer::arm() {
  armed_ = true;
  keys_.clear();
  setVisible(false);
}

void SettingsReapplyOffer::disarm() {
  armed_ = false;
  keys_.clear();
  setVisible(false);
}

void SettingsReapplyOffer::compare(const kapfix::v1::AgentState& state) {
  if (!armed_) return;
  keys_.clear();
  QStringList shown;
  for (const SettingsPanel::Difference& difference : settings_.differencesFrom(state)) {
    keys_ << difference.key;
    shown << tr("%1 is %2 (yours: %3)")
                 .arg(difference.key, Shown(difference.agent_value), difference.operator_value);
  }
  label_->setText(tr("The restarted agent's settings differ from yours: %1")
                      .arg(shown.join(QStringLiteral("; "))));
  setVisible(!keys_.isEmpty());
}

}  // namespace kapfix::station
