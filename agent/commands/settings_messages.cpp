#include "agent/commands/settings_messages.hpp"

#include <algorithm>

#include "agent/config/options_from_settings.hpp"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

// `settings` with every absent field present at its zero.
template <typename Settings>
Settings WithEveryField(Settings settings) {
  const google::protobuf::Descriptor& type = *settings.GetDescriptor();
  const google::protobuf::Reflection& r = *settings.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const google::protobuf::FieldDescriptor* field = type.field(i);
    if (field->is_repeated() || r.HasField(settings, field)) continue;
    switch (field->cpp_type()) {
      case google::protobuf::FieldDescriptor::CPPTYPE_FLOAT:
        r.SetFloat(&settings, field, 0);
        break;
      case google::protobuf::FieldDescriptor::CPPTYPE_DOUBLE:
        r.SetDouble(&settings, field, 0);
        break;
      case google::protobuf::FieldDescriptor::CPPTYPE_UINT32:
        r.SetUInt32(&settings, field, 0);
        break;
      case google::protobuf::FieldDescriptor::CPPTYPE_BOOL:
        r.SetBool(&settings, field, false);
        break;
      default:  // enums keep *_UNSPECIFIED, strings and messages stay absent
        break;
    }
  }
  return settings;
}

// A search command merged into the held search settings: every setting of SearchConfig seen
// as the message (its VisitFields), protobuf's merge, and copied back.
bool ApplySearch(const kapfix::v1::SearchSettings& s, SearchConfig* c, std::string* error) {
  kapfix::v1::SearchSettings held;
  if (!WriteSettings(*c, &held, error)) return false;
  kapfix::v1::MergeSettings(s, &held);
  return CopySettings(held, c, error);
}

// A lens by name switches to that stored profile; optics with a name define or update that
// profile (its deg/px then follows from them until it is calibrated).
bool ApplyLens(const kapfix::v1::LensProfile& l, AgentConfig* c, std::string* error) {
  const std::string name = l.has_name() ? l.name() : c->lens;
  auto profile = std::find_if(c->lenses.begin(), c->lenses.end(),
                              [&](const LensProfile& p) { return p.name == name; });
  if (profile == c->lenses.end()) {
    c->lenses.push_back(LensProfile{.name = name});
    profile = std::prev(c->lenses.end());
  }
  kapfix::v1::LensProfile optics = l;
  optics.clear_name();
  // Present fields serialise even at 0 (proto3 optional): any byte is an optic given.
  if (optics.ByteSizeLong() != 0) {
    kapfix::v1::LensProfile held;
    if (!WriteSettings(*profile, &held, error)) return false;
    kapfix::v1::MergeSettings(optics, &held);
    if (!CopySettings(held, &*profile, error)) return false;
    profile->deg_per_px_pan = 0;
    profile->deg_per_px_tilt = 0;
  }
  c->lens = name;
  return true;
}

}  // namespace

void FillSettings(const AgentConfig& config, kapfix::v1::AgentState* state) {
  *state->mutable_gains() = config.gains;

  *state->mutable_search() = SettingsFromOptions<kapfix::v1::SearchSettings>(config.search);

  // A camera setting left to the camera reads 0 (a state has every field).
  *state->mutable_camera() = WithEveryField(config.camera.settings);

  *state->mutable_lens() = SettingsFromOptions<kapfix::v1::LensProfile>(config.active_lens());

  *state->mutable_photo() = config.photo;
  *state->mutable_video() = config.video;
  state->set_frame_width_px(static_cast<std::uint32_t>(config.camera.width));
  state->set_frame_height_px(static_cast<std::uint32_t>(config.camera.height));
}

bool ApplySettingsCommand(const kapfix::v1::Command& command, AgentConfig* config,
                          std::string* error) {
  AgentConfig updated = *config;
  switch (command.command_case()) {
    case kapfix::v1::Command::kSetGains:
      kapfix::v1::MergeSettings(command.set_gains(), &updated.gains);
      break;
    case kapfix::v1::Command::kSetSearch:
      if (!ApplySearch(command.set_search(), &updated.search, error)) return false;
      break;
    case kapfix::v1::Command::kSetCamera:
      MergeCameraSettings(command.set_camera(), &updated.camera.settings);
      break;
    case kapfix::v1::Command::kSetLens:
      if (!ApplyLens(command.set_lens(), &updated, error)) return false;
      break;
    case kapfix::v1::Command::kSetVideo:
      kapfix::v1::MergeSettings(command.set_video(), &updated.video);
      break;
    case kapfix::v1::Command::kSetPhoto:
      kapfix::v1::MergeSettings(command.set_photo(), &updated.photo);
      break;
    default:
      if (error) *error = "not a settings command";
      return false;
  }
  if (!updated.IsValid(error)) return false;
  *config = std::move(updated);
  return true;
}

bool IsSettingsCommand(const kapfix::v1::Command& command) {
  switch (command.command_case()) {
    case kapfix::v1::Command::kSetGains:
    case kapfix::v1::Command::kSetSearch:
    case kapfix::v1::Command::kSetCamera:
    case kapfix::v1::Command::kSetLens:
    case kapfix::v1::Command::kSetVideo:
    case kapfix::v1::Command::kSetPhoto:
      return true;
    default:
      return false;
  }
}

}  // namespace kapfix::agent
