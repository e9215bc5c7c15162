#include "groundstation/settings/setting_row.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QSpinBox>

namespace kapfix::station {

SettingRow::SettingRow(const Spec& spec, const QString& help, QWidget* parent)
    : QWidget(parent), key_(spec.key), kind_(spec.kind), status_(new QLabel(this)) {
  setObjectName(QStringLiteral("setting_") + key_);
  auto emit_edit = [this] { emit edited(key_, value()); };
  switch (spec.kind) {
    case Kind::kReal: {
      auto* box = new QDoubleSpinBox(this);
      box->setRange(spec.minimum, spec.maximum);
      box->setDecimals(spec.decimals);
      box->setSingleStep(spec.step);
      // One command per finished edit (Enter, focus out, arrow step), not per keystroke.
      box->setKeyboardTracking(false);
      connect(box, &QDoubleSpinBox::valueChanged, this, emit_edit);
      editor_ = box;
      break;
    }
    case Kind::kInteger: {
      auto* box = new QSpinBox(this);
      box->setRange(static_cast<int>(spec.minimum), static_cast<int>(spec.maximum));
      box->setSingleStep(static_cast<int>(spec.step));
      box->setKeyboardTracking(false);
      connect(box, &QSpinBox::valueChanged, this, emit_edit);
      editor_ = box;
      break;
    }
    case Kind::kChoice: {
      auto* box = new QComboBox(this);
      box->addItems(spec.choices);
      connect(box, &QComboBox::activated, this, emit_edit);
      editor_ = box;
      break;
    }
    case Kind::kSwitch: {
      auto* box = new QCheckBox(this);
      connect(box, &QCheckBox::clicked, this, emit_edit);
      editor_ = box;
      break;
    }
    case Kind::kText: {
      auto* edit = new QLineEdit(this);
      connect(edit, &QLineEdit::editingFinished, this, [edit, emit_edit] {
        if (edit->isModified()) emit_edit();
        edit->setModified(false);
      });
      editor_ = edit;
      break;
    }
  }
  editor_->setObjectName(QStringLiteral("editor_") + key_);
  editor_->setToolTip(help);
  editor_->setMinimumWidth(110);
  status_->setObjectName(QStringLiteral("status_") + key_);
  status_->setWordWrap(true);
  status_->setMinimumWidth(24);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(editor_);
  layout->addWidget(status_, 1);
}

QString SettingRow::value() const {
  switch (kind_) {
    case Kind::kReal:
      return QString::number(static_cast<QDoubleSpinBox*>(editor_)->value(), 'g', 8);
    case Kind::kInteger:
      return QString::number(static_cast<QSpinBox*>(editor_)->value());
    case Kind::kChoice:
      return static_cast<QComboBox*>(editor_)->currentText();
    case Kind::kSwitch:
      return static_cast<QCheckBox*>(editor_)->isChecked() ? QStringLiteral("on")
                                                           : QStringLiteral("off");
    case Kind::kText:
      return static_cast<QLineEdit*>(editor_)->text();
  }
  return {};
}

void SettingRow::showAgentValue(const QString& value) {
  if (pending_) return;
  setEditorValue(value);
}

void SettingRow::setEditorValue(const QString& value) {
  const QSignalBlocker blocker(editor_);
  switch (kind_) {
    case Kind::kReal:
      static_cast<QDoubleSpinBox*>(editor_)->setValue(value.toDouble());
      break;
    case Kind::kInteger:
      static_cast<QSpinBox*>(editor_)->setValue(value.toInt());
      break;
    case Kind::kChoice:
      static_cast<QComboBox*>(editor_)->setCurrentText(value);
      break;
    case Kind::kSwitch:
      static_cast<QCheckBox*>(editor_)->setChecked(value == QStringLiteral("on"));
      break;
    case Kind::kText:
      static_cast<QLineEdit*>(editor_)->setText(value);
      break;
  }
}

void SettingRow::markPending() {
  pending_ = true;
  status_->setStyleSheet(QStringLiteral("color: #666;"));
  status_->setText(QStringLiteral("…"));
  status_->setToolTip(tr("Sent; waiting for the agent"));
}

void SettingRow::markAccepted() {
  pending_ = false;
  status_->setStyleSheet(QStringLiteral("color: #1e7b34; font-weight: bold;"));
  status_->setText(QStringLiteral("✓"));
  status_->setToolTip(tr("Accepted by the agent"));
}

void SettingRow::markRefused(const QString& reason) {
  pending_ = false;
  status_->setStyleSheet(QStringLiteral("color: #b3261e;"));
  status_->setText(reason);
  status_->setToolTip(tr("Refused by the agent: %1").arg(reason));
}

}  // namespace kapfix::station
