#include "groundstation/settings/settings_panel.hpp"

#include <QFormLayout>
#include <QGroupBox>
#include <QPointer>
#include <QScrollArea>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "groundstation/settings/calibration_view.hpp"
#include "groundstation/settings/setting_row.hpp"
#include "link/setting_key.hpp"

namespace kapfix::station {
namespace {

using google::protobuf::FieldDescriptor;
using kapfix::v1::AgentState;
using Kind = SettingRow::Kind;

// A setting as the panel shows it: its row, built from the settings schema (kind, range,
// unit, choices, help), and where its value is in an AgentState.
struct Entry {
  SettingRow::Spec spec;
  QString help;
  kapfix::v1::SettingEntry setting;
};

struct Group {
  QString title;
  std::vector<Entry> entries;
};

// Groups follow the command that carries the settings; camera, video and photos share one.
QString GroupTitle(const FieldDescriptor& command_field) {
  const std::string& name = command_field.name();
  if (name == "set_gains") return QStringLiteral("Controller");
  if (name == "set_search") return QStringLiteral("Search");
  if (name == "set_lens") return QStringLiteral("Lens");
  if (name == "set_photo") return QStringLiteral("Photos");
  return QStringLiteral("Camera and video");
}

// "dead_band" → "Dead band [px]".
QString Label(const kapfix::link::SettingKey& key) {
  QString label = QString::fromStdString(key.name).replace(QLatin1Char('_'), QLatin1Char(' '));
  label[0] = label[0].toUpper();
  const std::string& unit = key.entry.options->unit();
  if (!unit.empty())
    label += QStringLiteral(" [") + QString::fromStdString(unit) + QLatin1Char(']');
  return label;
}

QStringList Words(const google::protobuf::EnumDescriptor& type) {
  QStringList words;
  for (int i = 0; i < type.value_count(); ++i) {
    const std::string word = kapfix::v1::SettingWord(*type.value(i));
    if (!word.empty()) words << QString::fromStdString(word);
  }
  return words;
}

SettingRow::Spec SpecOf(const kapfix::link::SettingKey& key) {
  const FieldDescriptor& field = *key.entry.field;
  const kapfix::v1::SettingOptions& o = *key.entry.options;
  SettingRow::Spec spec;
  spec.key = QString::fromStdString(key.name);
  spec.label = Label(key);
  spec.kind = Kind::kText;
  // The row checks the schema's range (0 too where 0 means off); the step is about a
  // hundredth of it.
  spec.minimum = o.min();
  spec.maximum = o.max();
  spec.zero_means_off = o.zero_means_off();
  spec.unit = QString::fromStdString(o.unit());
  spec.help = QString::fromStdString(o.help());
  spec.step =
      o.max() > o.min() ? std::pow(10.0, std::floor(std::log10(o.max() - o.min())) - 2) : 1.0;
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
      spec.kind = Kind::kReal;
      spec.decimals = std::max(1, static_cast<int>(std::ceil(-std::log10(spec.step))));
      break;
    case FieldDescriptor::CPPTYPE_UINT32:
      spec.kind = Kind::kInteger;
      spec.step = std::max(1.0, spec.step);
      break;
    case FieldDescriptor::CPPTYPE_ENUM:
      spec.kind = Kind::kChoice;
      spec.choices = Words(*field.enum_type());
      break;
    case FieldDescriptor::CPPTYPE_BOOL:
      spec.kind = Kind::kSwitch;
      break;
    default:
      spec.kind = Kind::kText;
      break;
  }
  // The one setting with a special editor: the strategies are names, not an enum.
  if (key.name == "strategy") {
    spec.kind = Kind::kChoice;
    spec.choices = {QStringLiteral("all"), QStringLiteral("h23"), QStringLiteral("h21"),
                    QStringLiteral("h19"), QStringLiteral("h17"), QStringLiteral("h15"),
                    QStringLiteral("pyr")};
  }
  return spec;
}

// The agent's reason in the operator's words: the field's name in the command
// ("set_camera.gain_db = 99: must be in [0, 48] dB") becomes what the setting is ("camera
// analogue gain = 99: ...").
QString PlainReason(const QString& reason, const kapfix::v1::SettingEntry& setting,
                    const QString& help) {
  QString name = QString::fromStdString(setting.command_field->name());
  if (setting.field != setting.command_field) {
    name += QLatin1Char('.') + QString::fromStdString(setting.field->name());
  }
  QString plain = reason;
  plain.replace(name, help);
  return plain;
}

// A setting's value in the agent's state, as setting text: AgentState holds each settings
// message under the command's name without "set_" (set_gains → gains).
QString ValueIn(const AgentState& state, const kapfix::v1::SettingEntry& setting) {
  const auto* in_state =
      AgentState::descriptor()->FindFieldByName(setting.command_field->name().substr(4));
  if (in_state == nullptr) return {};
  const google::protobuf::Message* holder = &state;
  const FieldDescriptor* field = in_state;
  if (setting.field != setting.command_field) {
    holder = &state.GetReflection()->GetMessage(state, in_state);
    field = setting.field;
  }
  const auto& r = *holder->GetReflection();
  switch (field->cpp_type()) {
    case FieldDescriptor::CPPTYPE_FLOAT:
      return QString::number(r.GetFloat(*holder, field), 'g', 8);
    case FieldDescriptor::CPPTYPE_UINT32:
      return QString::number(r.GetUInt32(*holder, field));
    case FieldDescriptor::CPPTYPE_BOOL:
      return r.GetBool(*holder, field) ? QStringLiteral("on") : QStringLiteral("off");
    case FieldDescriptor::CPPTYPE_ENUM:
      return QString::fromStdString(kapfix::v1::SettingWord(*r.GetEnum(*holder, field)));
    case FieldDescriptor::CPPTYPE_STRING:
      return QString::fromStdString(r.GetString(*holder, field));
    default:
      return {};
  }
}

// The agent reports a float, the operator typed a decimal: "0.60000002" is "0.6".
bool SameValue(const QString& a, const QString& b) {
  bool a_number = false;
  bool b_number = false;
  const double x = a.toDouble(&a_number);
  const double y = b.toDouble(&b_number);
  if (a_number && b_number) return static_cast<float>(x) == static_cast<float>(y);
  return a == b;
}

std::vector<Group> Groups() {
  std::vector<Group> groups;
  for (const kapfix::link::SettingKey& key : kapfix::link::SettingKeys()) {
    const QString title = GroupTitle(*key.entry.command_field);
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&title](const Group& g) { return g.title == title; });
    if (group == groups.end()) {
      groups.push_back({title, {}});
      group = std::prev(groups.end());
    }
    group->entries.push_back({SpecOf(key), QString::fromStdString(key.help), key.entry});
  }
  return groups;
}

const std::vector<Group>& TheGroups() {
  static const std::vector<Group> groups = Groups();
  return groups;
}

const Entry* EntryOf(const QString& key) {
  for (const Group& group : TheGroups()) {
    for (const Entry& entry : group.entries) {
      if (entry.spec.key == key) return &entry;
    }
  }
  return nullptr;
}

}  // namespace

SettingsPanel::SettingsPanel(AgentClient& client, QWidget* parent)
    : QWidget(parent), client_(client), calibration_(new CalibrationView(client, this)) {
  auto* content = new QWidget(this);
  auto* column = new QVBoxLayout(content);
  for (const Group& group : TheGroups()) {
    auto* box = new QGroupBox(group.title, content);
    auto* form = new QFormLayout(box);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    for (const Entry& entry : group.entries) {
      auto* row = new SettingRow(entry.spec, entry.help, box);
      form->addRow(entry.spec.label, row);
      rows_.insert(row->key(), row);
      connect(row, &SettingRow::edited, this, &SettingsPanel::send);
    }
    if (group.title == QStringLiteral("Lens")) form->addRow(calibration_);
    column->addWidget(box);
  }
  column->addStretch(1);
  auto* scroll = new QScrollArea(this);
  scroll->setWidget(content);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(scroll);

  connect(&client_, &AgentClient::stateReceived, this, &SettingsPanel::showState);
}

void SettingsPanel::send(const QString& key, const QString& value) {
  SettingRow* setting = row(key);
  std::string error;
  auto command = kapfix::link::MakeSetCommand(key.toStdString(), value.toStdString(), &error);
  if (!command) {
    setting->markRefused(QString::fromStdString(error));
    return;
  }
  setting->markPending();
  client_.sendCommand(std::move(*command), [self = QPointer(this), setting = QPointer(setting), key,
                                            value](const CommandOutcome& outcome) {
    if (self.isNull() || setting.isNull()) return;
    if (outcome.ok) {
      self->operator_values_.insert(key, value);
      setting->markAccepted();
    } else {
      const Entry* entry = EntryOf(key);
      setting->markRefused(entry == nullptr
                               ? outcome.reason
                               : PlainReason(outcome.reason, entry->setting, entry->spec.help));
    }
  });
}

std::vector<SettingsPanel::Difference> SettingsPanel::differencesFrom(
    const AgentState& state) const {
  std::vector<Difference> differences;
  for (const Group& group : TheGroups()) {
    for (const Entry& entry : group.entries) {
      const auto mine = operator_values_.constFind(entry.spec.key);
      if (mine == operator_values_.constEnd()) continue;
      const QString agent = ValueIn(state, entry.setting);
      if (!SameValue(agent, *mine)) differences.push_back({entry.spec.key, agent, *mine});
    }
  }
  return differences;
}

void SettingsPanel::reapply(const QStringList& keys) {
  for (const QString& key : keys) {
    const auto mine = operator_values_.constFind(key);
    if (mine == operator_values_.constEnd() || row(key) == nullptr) continue;
    row(key)->restoreOperatorValue(*mine);
    send(key, *mine);
  }
}

void SettingsPanel::showState(const AgentState& state) {
  for (const Group& group : TheGroups()) {
    for (const Entry& entry : group.entries) {
      if (SettingRow* setting = row(entry.spec.key)) {
        setting->showAgentValue(ValueIn(state, entry.setting));
      }
    }
  }
}

}  // namespace kapfix::station
