#include "groundstation/settings/setting_row.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QVBoxLayout>
#include <cmath>

namespace kapfix::station {
namespace {

// [1] how far beyond the schema's range the editor itself goes: far enough that any number
// an operator types stays as typed (and is refused by the row), not clamped by the editor.
constexpr double kEditorReach = 1e9;

// A spin box whose own range is far wider than the setting's (see kEditorReach), sized for
// the setting's range rather than for its own.
template <typename Box>
class WideBox final : public Box {
 public:
  WideBox(QString widest, QWidget* parent) : Box(parent), widest_(std::move(widest)) {}

  QSize sizeHint() const override { return narrowed(Box::sizeHint()); }
  QSize minimumSizeHint() const override { return narrowed(Box::minimumSizeHint()); }

 private:
  // Qt sizes a spin box for the text of its minimum and maximum: that width is replaced by
  // the setting's widest value.
  QSize narrowed(QSize size) const {
    const QFontMetrics metrics = this->fontMetrics();
    const int own = std::max(metrics.horizontalAdvance(this->textFromValue(this->minimum())),
                             metrics.horizontalAdvance(this->textFromValue(this->maximum())));
    const int wanted = metrics.horizontalAdvance(widest_);
    if (own > wanted) size.setWidth(size.width() - own + wanted);
    return size;
  }

  QString widest_;
};

QString Number(double value) { return QString::number(value, 'g', 8); }

// "0 to 48 dB", "0 (off) or 0.1 to 60 fps", "1 to 64".
QString RangeWords(const SettingRow::Spec& spec) {
  QString words = QObject::tr("%1 to %2").arg(Number(spec.minimum), Number(spec.maximum));
  if (spec.zero_means_off) words = QObject::tr("0 (off) or %1").arg(words);
  if (!spec.unit.isEmpty() && spec.unit != QStringLiteral("1"))
    words += QLatin1Char(' ') + spec.unit;
  return words;
}

// The widest value of the range as the editor writes it, with two characters to spare.
QString Widest(const SettingRow::Spec& spec, int decimals) {
  const QString low = QString::number(spec.minimum, 'f', decimals);
  const QString high = QString::number(spec.maximum, 'f', decimals);
  return (low.size() > high.size() ? low : high) + QStringLiteral("00");
}

}  // namespace

SettingRow::SettingRow(const Spec& spec, const QString& help, QWidget* parent)
    : QWidget(parent),
      key_(spec.key),
      kind_(spec.kind),
      minimum_(spec.minimum),
      maximum_(spec.maximum),
      zero_means_off_(spec.zero_means_off),
      range_words_(RangeWords(spec)),
      help_(spec.help),
      status_(new QLabel(this)),
      hint_(new QLabel(this)) {
  setObjectName(QStringLiteral("setting_") + key_);
  auto emit_edit = [this] { emit edited(key_, value()); };
  switch (spec.kind) {
    case Kind::kReal: {
      auto* box = new WideBox<QDoubleSpinBox>(Widest(spec, spec.decimals), this);
      box->setDecimals(spec.decimals);
      box->setRange(-kEditorReach, kEditorReach);
      box->setSingleStep(spec.step);
      // One command per finished edit (Enter, focus out, arrow step), not per keystroke.
      box->setKeyboardTracking(false);
      connect(box, &QDoubleSpinBox::valueChanged, this, &SettingRow::numberEdited);
      editor_ = box;
      break;
    }
    case Kind::kInteger: {
      auto* box = new WideBox<QSpinBox>(Widest(spec, 0), this);
      box->setRange(-static_cast<int>(kEditorReach), static_cast<int>(kEditorReach));
      box->setSingleStep(static_cast<int>(spec.step));
      box->setKeyboardTracking(false);
      connect(box, &QSpinBox::valueChanged, this,
              [this](int value) { numberEdited(static_cast<double>(value)); });
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
  hint_->setObjectName(QStringLiteral("hint_") + key_);
  hint_->setStyleSheet(QStringLiteral("color: #5f6368;"));
  hint_->setToolTip(help);
  const bool number = kind_ == Kind::kReal || kind_ == Kind::kInteger;
  hint_->setText(number ? range_words_ : QString());
  hint_->setVisible(number);
  auto* line = new QHBoxLayout;
  line->setContentsMargins(0, 0, 0, 0);
  line->addWidget(editor_);
  line->addWidget(status_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addLayout(line);
  layout->addWidget(hint_);
}

bool SettingRow::inRange(double value) const {
  if (zero_means_off_ && value == 0) return true;
  return std::isfinite(value) && value >= minimum_ && value <= maximum_;
}

void SettingRow::numberEdited(double number) {
  if (!inRange(number)) {
    markOutOfRange(true);
    status_->setStyleSheet(QStringLiteral("color: #b3261e; font-weight: bold;"));
    status_->setText(
        tr("%1 is not possible: %2 takes %3").arg(Number(number), help_, range_words_));
    status_->setToolTip(status_->text());
    return;
  }
  markOutOfRange(false);
  emit edited(key_, value());
}

void SettingRow::markOutOfRange(bool out) {
  out_of_range_ = out;
  editor_->setStyleSheet(out ? QStringLiteral("border: 2px solid #b3261e;") : QString());
  if (!out) status_->clear();
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
  // Neither a change on its way nor a value the operator is still fixing is overwritten.
  if (pending_ || out_of_range_ || refused_) return;
  setEditorValue(value);
}

void SettingRow::restoreOperatorValue(const QString& value) {
  refused_ = false;
  markOutOfRange(false);
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
  refused_ = false;
  editor_->setStyleSheet(QString());
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
  // The refused value stays in the editor, marked, until the operator changes it: the
  // agent's value does not silently take its place.
  refused_ = true;
  editor_->setStyleSheet(QStringLiteral("border: 2px solid #b3261e;"));
  status_->setStyleSheet(QStringLiteral("color: #b3261e;"));
  status_->setText(reason);
  status_->setToolTip(tr("Refused by the agent: %1").arg(reason));
}

}  // namespace kapfix::station
