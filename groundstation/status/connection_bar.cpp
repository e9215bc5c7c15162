#include "groundstation/status/connection_bar.hpp"

#include <QHBoxLayout>
#include <QLabel>
#include <QSettings>

#include "groundstation/client/zmq_agent_client.hpp"

namespace kapfix::station {

ConnectionBar::ConnectionBar(ZmqAgentClient& client, QWidget* parent)
    : QWidget(parent),
      client_(client),
      host_(new QLineEdit(this)),
      command_port_(new QSpinBox(this)),
      stream_port_(new QSpinBox(this)),
      connect_(new QPushButton(tr("Connect"), this)) {
  host_->setPlaceholderText(tr("agent host"));
  host_->setToolTip(tr("Host name or address of the kapfix-agent (Ctrl+L)"));
  host_->setMinimumWidth(160);
  host_->setMaximumWidth(280);
  for (QSpinBox* port : {command_port_, stream_port_}) {
    port->setRange(1, 65535);
    port->setButtonSymbols(QAbstractSpinBox::NoButtons);
    port->setFixedWidth(port->fontMetrics().horizontalAdvance(QStringLiteral("655350")) + 12);
  }
  command_port_->setToolTip(tr("Agent command port (ROUTER)"));
  stream_port_->setToolTip(tr("Agent stream port (PUB)"));
  setSizePolicy(QSizePolicy::Maximum, QSizePolicy::Fixed);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(new QLabel(tr("Agent"), this));
  layout->addWidget(host_);
  layout->addWidget(command_port_);
  layout->addWidget(stream_port_);
  layout->addWidget(connect_);
  setAddress(AgentAddress::load(QSettings()));
  connect(connect_, &QPushButton::clicked, this, &ConnectionBar::connectToAgent);
  connect(host_, &QLineEdit::returnPressed, this, &ConnectionBar::connectToAgent);
}

AgentAddress ConnectionBar::address() const {
  AgentAddress address;
  address.host = host_->text().trimmed();
  address.command_port = command_port_->value();
  address.stream_port = stream_port_->value();
  return address;
}

void ConnectionBar::setAddress(const AgentAddress& address) {
  host_->setText(address.host);
  command_port_->setValue(address.command_port);
  stream_port_->setValue(address.stream_port);
}

bool ConnectionBar::connectToAgent() {
  const AgentAddress wanted = address();
  QString error;
  if (wanted.host.isEmpty() || !client_.connectTo(wanted, &error)) {
    host_->setToolTip(tr("Cannot connect: %1").arg(error.isEmpty() ? tr("no host") : error));
    host_->setStyleSheet(QStringLiteral("QLineEdit { border: 2px solid #b3261e; }"));
    return false;
  }
  host_->setStyleSheet(QString());
  QSettings settings;
  wanted.save(settings);
  return true;
}

}  // namespace kapfix::station
