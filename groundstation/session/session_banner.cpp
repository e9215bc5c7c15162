#include "groundstation/session/session_banner.hpp"

#include <QHBoxLayout>
#include <QTime>

#include "groundstation/status/mode_name.hpp"

namespace kapfix::station {
namespace {

constexpr int kTickMs = 250;  // [ms] age refresh while the link is down

}  // namespace

SessionBanner::SessionBanner(AgentClient& client, QWidget* parent)
    : QWidget(parent), label_(new QLabel(this)), dismiss_(new QPushButton(tr("Dismiss"), this)) {
  setObjectName(QStringLiteral("sessionBanner"));
  setAttribute(Qt::WA_StyledBackground);
  label_->setTextFormat(Qt::PlainText);
  label_->setWordWrap(true);
  QFont big = label_->font();
  big.setBold(true);
  big.setPointSizeF(big.pointSizeF() * 1.3);
  label_->setFont(big);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(8, 4, 8, 4);
  layout->addWidget(label_, 1);
  layout->addWidget(dismiss_);
  dismiss_->setToolTip(tr("The operator has seen the restart"));
  connect(dismiss_, &QPushButton::clicked, this, [this] {
    restart_session_ = 0;
    refresh();
  });
  tick_.setInterval(kTickMs);
  connect(&tick_, &QTimer::timeout, this, &SessionBanner::refresh);
  link_ = client.linkState();
  connect(&client, &AgentClient::linkChanged, this, [this](const LinkState& state) {
    if (state.up && !state.replay) heard_ = true;
    link_ = state;
    refresh();
  });
  connect(&client, &AgentClient::messageReceived, this,
          [this](const QString& /*topic*/, const QByteArray& /*payload*/, qint64 /*time_us*/) {
            last_heard_.restart();
          });
  connect(&client, &AgentClient::stateReceived, this, [this](const kapfix::v1::AgentState& state) {
    const bool changed = state.resumed() != state_.resumed() || state.mode() != state_.mode() ||
                         state.slice() != state_.slice();
    state_ = state;
    if (changed && restart_session_ > 0) refresh();
  });
  refresh();
}

void SessionBanner::announceRestart(int session) {
  restart_session_ = session;
  restart_time_ = QTime::currentTime().toString(QStringLiteral("HH:mm:ss"));
  state_.set_resumed(false);  // the old agent's state says nothing about the new one
  refresh();
}

QString SessionBanner::restartText() const {
  const QString head =
      tr("AGENT RESTARTED at %1 (session %2): ").arg(restart_time_).arg(restart_session_);
  const QString tail = tr("; the panels now show only the new session.");
  if (!state_.resumed()) return head + tr("it starts Idle and may have lost its settings") + tail;
  const QString where = state_.slice() > 0 ? tr(" on slice %1").arg(state_.slice()) : QString();
  return head + tr("it RESUMED %1%2 from its stored state").arg(ModeName(state_.mode()), where) +
         tail;
}

void SessionBanner::setPrompt(const QString& prompt) {
  prompt_ = prompt;
  refresh();
}

void SessionBanner::refresh() {
  QString text;
  QString colour;
  bool dismissable = false;
  const bool down = heard_ && !link_.up && !link_.replay;
  if (!prompt_.isEmpty()) {
    text = prompt_;
    colour = QStringLiteral("#8a6d00");
  } else if (down) {
    const double age_s =
        last_heard_.isValid() ? static_cast<double>(last_heard_.elapsed()) / 1000.0 : 0.0;
    text = tr("LINK DOWN: nothing from the agent for %1 s; every value shown is the last heard")
               .arg(age_s, 0, 'f', 0);
    colour = QStringLiteral("#b3261e");
  } else if (restart_session_ > 0) {
    text = restartText();
    colour = QStringLiteral("#b35c00");
    dismissable = true;
  } else if (link_.replay) {
    text = tr("REPLAY of %1: a recording, not the live agent").arg(link_.source);
    colour = QStringLiteral("#1f5fbf");
  }
  if (down) {
    if (!tick_.isActive()) tick_.start();
  } else {
    tick_.stop();
  }
  label_->setText(text);
  dismiss_->setVisible(dismissable);
  setStyleSheet(
      QStringLiteral("#sessionBanner { background: %1; } QLabel { color: white; }").arg(colour));
  setVisible(!text.isEmpty());
}

}  // namespace kapfix::station
