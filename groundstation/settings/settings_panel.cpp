#include "groundstation/settings/settings_panel.hpp"

#include <QFormLayout>
#include <QGroupBox>
#include <QPointer>
#include <QScrollArea>
#include <QVBoxLayout>
#include <functional>
#include <string>
#include <vector>

#include "groundstation/settings/calibration_view.hpp"
#include "groundstation/settings/setting_row.hpp"
#include "tools/ctl/setting_key.hpp"

namespace kapfix::station {
namespace {

using kapfix::v1::AgentState;
using Kind = SettingRow::Kind;

// A setting as the panel shows it: its row, and how to read its value from an AgentState.
struct Entry {
  SettingRow::Spec spec;
  std::function<QString(const AgentState&)> read;
};

struct Group {
  const char* title;
  std::vector<Entry> entries;
};

QString Real(double value) { return QString::number(value, 'g', 8); }
QString Switch(bool on) { return on ? QStringLiteral("on") : QStringLiteral("off"); }

QString ControllerWord(kapfix::v1::ControllerKind kind) {
  switch (kind) {
    case kapfix::v1::CONTROLLER_KIND_P:
      return QStringLiteral("p");
    case kapfix::v1::CONTROLLER_KIND_PID:
      return QStringLiteral("pid");
    case kapfix::v1::CONTROLLER_KIND_PREDICTIVE:
      return QStringLiteral("predictive");
    default:
      return {};
  }
}

QString SamplingWord(kapfix::v1::Sampling sampling) {
  switch (sampling) {
    case kapfix::v1::SAMPLING_ALL:
      return QStringLiteral("all");
    case kapfix::v1::SAMPLING_STATIC:
      return QStringLiteral("static");
    case kapfix::v1::SAMPLING_RANDOM:
      return QStringLiteral("random");
    default:
      return {};
  }
}

QString AxisWord(kapfix::v1::Axis axis) {
  switch (axis) {
    case kapfix::v1::AXIS_X:
      return QStringLiteral("x");
    case kapfix::v1::AXIS_Y:
      return QStringLiteral("y");
    case kapfix::v1::AXIS_BOTH:
      return QStringLiteral("both");
    default:
      return {};
  }
}

QString ChannelWord(kapfix::v1::Channel channel) {
  switch (channel) {
    case kapfix::v1::CHANNEL_GREEN:
      return QStringLiteral("green");
    case kapfix::v1::CHANNEL_RGB_SUM:
      return QStringLiteral("rgb");
    default:
      return {};
  }
}

QString ScoreWord(kapfix::v1::SliceScoreKind kind) {
  switch (kind) {
    case kapfix::v1::SLICE_SCORE_KIND_DC:
      return QStringLiteral("dc");
    case kapfix::v1::SLICE_SCORE_KIND_DC_HYSTERESIS:
      return QStringLiteral("dc_hysteresis");
    case kapfix::v1::SLICE_SCORE_KIND_SINGLE_SHOT:
      return QStringLiteral("single_shot");
    default:
      return {};
  }
}

SettingRow::Spec RealSpec(const char* key, const char* label, double minimum, double maximum,
                          int decimals, double step) {
  SettingRow::Spec spec{key, label, Kind::kReal, minimum, maximum, decimals, step, {}};
  return spec;
}

SettingRow::Spec IntegerSpec(const char* key, const char* label, double minimum, double maximum,
                             double step) {
  SettingRow::Spec spec{key, label, Kind::kInteger, minimum, maximum, 0, step, {}};
  return spec;
}

SettingRow::Spec Choice(const char* key, const char* label, QStringList choices) {
  SettingRow::Spec spec{key, label, Kind::kChoice, 0, 0, 0, 0, std::move(choices)};
  return spec;
}

SettingRow::Spec SwitchSpec(const char* key, const char* label) {
  SettingRow::Spec spec{key, label, Kind::kSwitch, 0, 0, 0, 0, {}};
  return spec;
}

SettingRow::Spec TextSpec(const char* key, const char* label) {
  SettingRow::Spec spec{key, label, Kind::kText, 0, 0, 0, 0, {}};
  return spec;
}

// Editor ranges only keep typing sane; the agent's CommandValidator owns the real limits.
std::vector<Group> Groups() {
  return {
      {QT_TRANSLATE_NOOP("SettingsPanel", "Controller"),
       {
           {Choice("controller", "Controller",
                   {QStringLiteral("p"), QStringLiteral("pid"), QStringLiteral("predictive")}),
            [](const AgentState& s) { return ControllerWord(s.gains().controller()); }},
           {RealSpec("p", "P [1]", 0, 10, 3, 0.05),
            [](const AgentState& s) { return Real(s.gains().p()); }},
           {RealSpec("i", "I [1/s]", 0, 100, 3, 0.05),
            [](const AgentState& s) { return Real(s.gains().i()); }},
           {RealSpec("d", "D [s]", 0, 10, 3, 0.01),
            [](const AgentState& s) { return Real(s.gains().d()); }},
           {RealSpec("dead_band", "Dead band [px]", 0, 100, 1, 0.5),
            [](const AgentState& s) { return Real(s.gains().dead_band_px()); }},
           {RealSpec("rate_limit", "Rate limit [deg/s]", 0, 2000, 0, 10),
            [](const AgentState& s) { return Real(s.gains().rate_limit_deg_per_s()); }},
       }},
      {QT_TRANSLATE_NOOP("SettingsPanel", "Search"),
       {
           {Choice("strategy", "Strategy",
                   {QStringLiteral("all"), QStringLiteral("h23"), QStringLiteral("h21"),
                    QStringLiteral("h19"), QStringLiteral("h17"), QStringLiteral("h15"),
                    QStringLiteral("pyr")}),
            [](const AgentState& s) { return QString::fromStdString(s.search().strategy()); }},
           {Choice("sampling", "Sampling",
                   {QStringLiteral("all"), QStringLiteral("static"), QStringLiteral("random")}),
            [](const AgentState& s) { return SamplingWord(s.search().sampling()); }},
           {RealSpec("random_fraction", "Random share [1]", 0.01, 1, 2, 0.05),
            [](const AgentState& s) { return Real(s.search().random_fraction()); }},
           {IntegerSpec("patch_size", "Patch size [px]", 8, 1200, 10),
            [](const AgentState& s) { return QString::number(s.search().patch_size_px()); }},
           {IntegerSpec("slice_count", "Slices [count]", 1, 50, 1),
            [](const AgentState& s) { return QString::number(s.search().slice_count()); }},
           {Choice("axis", "Search axis",
                   {QStringLiteral("x"), QStringLiteral("y"), QStringLiteral("both")}),
            [](const AgentState& s) { return AxisWord(s.search().axis()); }},
           {IntegerSpec("range", "Range R [px]", 1, 800, 10),
            [](const AgentState& s) { return QString::number(s.search().search_range_px()); }},
           {SwitchSpec("subpixel", "Sub-pixel"),
            [](const AgentState& s) { return Switch(s.search().subpixel()); }},
           {Choice("channel", "Channel", {QStringLiteral("green"), QStringLiteral("rgb")}),
            [](const AgentState& s) { return ChannelWord(s.search().channel()); }},
           {Choice("slice_score", "Slice score",
                   {QStringLiteral("dc"), QStringLiteral("dc_hysteresis"),
                    QStringLiteral("single_shot")}),
            [](const AgentState& s) { return ScoreWord(s.search().slice_score()); }},
           {RealSpec("hysteresis", "DC hysteresis [px]", 0, 50, 1, 0.5),
            [](const AgentState& s) { return Real(s.search().dc_hysteresis_px()); }},
       }},
      {QT_TRANSLATE_NOOP("SettingsPanel", "Camera and video"),
       {
           {RealSpec("gain", "Gain [dB]", -20, 60, 1, 1),
            [](const AgentState& s) { return Real(s.camera().gain_db()); }},
           {RealSpec("exposure", "Exposure [µs]", 1, 1e6, 0, 100),
            [](const AgentState& s) { return Real(s.camera().exposure_us()); }},
           {SwitchSpec("auto_exposure", "Auto exposure"),
            [](const AgentState& s) { return Switch(s.camera().auto_exposure()); }},
           {RealSpec("video_fps", "Video rate [fps]", 0, 120, 1, 1),
            [](const AgentState& s) { return Real(s.video().fps()); }},
           {IntegerSpec("jpeg_quality", "JPEG quality [1..100]", 1, 100, 5),
            [](const AgentState& s) { return QString::number(s.video().jpeg_quality()); }},
           {RealSpec("video_scale", "Video scale [1]", 0.05, 1, 2, 0.05),
            [](const AgentState& s) { return Real(s.video().scale()); }},
       }},
      {QT_TRANSLATE_NOOP("SettingsPanel", "Lens"),
       {
           {TextSpec("lens", "Profile"),
            [](const AgentState& s) { return QString::fromStdString(s.lens().name()); }},
           {RealSpec("focal_length", "Focal length [mm]", 0, 200, 2, 0.5),
            [](const AgentState& s) { return Real(s.lens().focal_length_mm()); }},
           {RealSpec("pixel_pitch", "Pixel pitch [µm]", 0, 50, 2, 0.1),
            [](const AgentState& s) { return Real(s.lens().pixel_pitch_um()); }},
       }},
  };
}

const std::vector<Group>& TheGroups() {
  static const std::vector<Group> groups = Groups();
  return groups;
}

QString HelpOf(const char* key) {
  for (const auto& setting : kapfix::ctl::SettingKeys()) {
    if (setting.name == key)
      return QString::fromUtf8(setting.help.data(), static_cast<qsizetype>(setting.help.size()));
  }
  return {};
}

}  // namespace

SettingsPanel::SettingsPanel(AgentClient& client, QWidget* parent)
    : QWidget(parent), client_(client), calibration_(new CalibrationView(client, this)) {
  auto* content = new QWidget(this);
  auto* column = new QVBoxLayout(content);
  for (const Group& group : TheGroups()) {
    auto* box = new QGroupBox(tr(group.title), content);
    auto* form = new QFormLayout(box);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    for (const Entry& entry : group.entries) {
      auto* row = new SettingRow(entry.spec, HelpOf(entry.spec.key), box);
      form->addRow(tr(entry.spec.label), row);
      rows_.insert(row->key(), row);
      connect(row, &SettingRow::edited, this, &SettingsPanel::send);
    }
    if (QLatin1String(group.title) == QLatin1String("Lens")) form->addRow(calibration_);
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
  auto command = kapfix::ctl::MakeSetCommand(key.toStdString(), value.toStdString(), &error);
  if (!command) {
    setting->markRefused(QString::fromStdString(error));
    return;
  }
  setting->markPending();
  client_.sendCommand(std::move(*command),
                      [setting = QPointer(setting)](const CommandOutcome& outcome) {
                        if (setting.isNull()) return;
                        if (outcome.ok) {
                          setting->markAccepted();
                        } else {
                          setting->markRefused(outcome.reason);
                        }
                      });
}

void SettingsPanel::showState(const AgentState& state) {
  for (const Group& group : TheGroups()) {
    for (const Entry& entry : group.entries) {
      if (SettingRow* setting = row(QLatin1String(entry.spec.key))) {
        setting->showAgentValue(entry.read(state));
      }
    }
  }
}

}  // namespace kapfix::station
