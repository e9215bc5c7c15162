#include "groundstation/status/link_status_bar.hpp"

#include <QHBoxLayout>
#include <cmath>

#include "groundstation/status/mode_name.hpp"

namespace kapfix::station {
namespace {

QLabel* Field(QWidget* parent, const QString& tooltip) {
  auto* label = new QLabel(parent);
  label->setToolTip(tooltip);
  label->setTextFormat(Qt::PlainText);
  label->setMargin(4);
  return label;
}

}  // namespace

LinkStatusBar::LinkStatusBar(AgentClient& client, QWidget* parent)
    : QWidget(parent),
      link_(Field(this, tr("Link to the agent: up while its messages arrive"))),
      latency_(Field(this, tr("Heartbeat round trip [ms]"))),
      fps_(Field(this, tr("Frames the agent processes per second"))),
      mode_(Field(this, tr("What the agent is doing"))),
      slice_(Field(this, tr("Slice in use, 1 = top"))),
      source_(Field(this, tr("Agent endpoint or replayed recording"))) {
  setObjectName(QStringLiteral("linkStatusBar"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  for (QLabel* label : {link_, latency_, fps_, mode_, slice_}) {
    // Room for the widest usual value, so the line does not jump; not more (1366 px laptops).
    label->setMinimumWidth(label->fontMetrics().horizontalAdvance(QStringLiteral("NOT CONNECTED")) /
                           (label == link_ ? 1 : 2));
    layout->addWidget(label);
  }
  layout->addStretch(1);
  layout->addWidget(source_);
  QFont bold = link_->font();
  bold.setBold(true);
  link_->setFont(bold);
  mode_->setFont(bold);

  showLink(client.linkState());
  fps_->setText(tr("— fps"));
  showMode(kapfix::v1::MODE_UNSPECIFIED);
  slice_->setText(tr("Slice —"));
  connect(&client, &AgentClient::linkChanged, this, &LinkStatusBar::showLink);
  connect(&client, &AgentClient::telemetryReceived, this, &LinkStatusBar::showTelemetry);
  connect(&client, &AgentClient::stateReceived, this, [this](const kapfix::v1::AgentState& state) {
    resumed_ = state.resumed();
    showMode(state.mode());
  });
}

void LinkStatusBar::showLink(const LinkState& state) {
  QString colour;
  if (state.replay) {
    link_->setText(tr("REPLAY"));
    colour = QStringLiteral("#1f5fbf");
  } else if (state.up) {
    link_->setText(tr("LINK UP"));
    colour = QStringLiteral("#1e7b34");
  } else {
    link_->setText(state.source.isEmpty()              ? tr("NOT CONNECTED")
                   : state.handshake_failure.isEmpty() ? tr("LINK DOWN")
                                                       : tr("KEY REFUSED"));
    colour = QStringLiteral("#b3261e");
  }
  link_->setStyleSheet(
      QStringLiteral("QLabel { color: white; background: %1; border-radius: 4px; }").arg(colour));
  latency_->setText(state.up && state.latency_us >= 0
                        ? tr("%1 ms").arg(static_cast<double>(state.latency_us) / 1000.0, 0, 'f', 1)
                        : tr("— ms"));
  QString source = state.source;
  if (!state.agent_id.isEmpty()) source = state.agent_id + QStringLiteral(" @ ") + source;
  if (state.sequence_gaps > 0) source += tr("  (%1 lost)").arg(state.sequence_gaps);
  if (!state.up && !state.handshake_failure.isEmpty()) {
    source += QStringLiteral(": ") + state.handshake_failure;
  }
  source_->setText(source);
  greyed_ = !state.up && !state.replay;
  for (QLabel* label : {fps_, mode_, slice_}) {
    label->setStyleSheet(greyed_ ? QStringLiteral("QLabel { color: #9aa0a6; }") : QString());
  }
}

void LinkStatusBar::showTelemetry(const kapfix::v1::Telemetry& telemetry) {
  fps_->setText(tr("%1 fps").arg(static_cast<double>(telemetry.fps()), 0, 'f', 1));
  showMode(telemetry.mode());
  slice_->setText(telemetry.slice() > 0 ? tr("Slice %1").arg(telemetry.slice()) : tr("Slice —"));
}

void LinkStatusBar::showMode(kapfix::v1::Mode mode) {
  // A resumed agent came back by itself in the mode it had: said so, so that the operator
  // does not take it for a mode they chose in this session.
  mode_->setText(resumed_ ? tr("%1 (resumed)").arg(ModeName(mode)) : ModeName(mode));
}

}  // namespace kapfix::station
