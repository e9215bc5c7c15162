#include "agent/commands/settings_messages.hpp"

#include <algorithm>

#include "agent/modes/report_messages.hpp"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

kapfix::v1::Sampling ToProto(SamplingKind kind) {
  switch (kind) {
    case SamplingKind::kAll:
      return kapfix::v1::SAMPLING_ALL;
    case SamplingKind::kStatic:
      return kapfix::v1::SAMPLING_STATIC;
    case SamplingKind::kRandom:
      return kapfix::v1::SAMPLING_RANDOM;
  }
  return kapfix::v1::SAMPLING_UNSPECIFIED;
}

kapfix::v1::Axis ToProto(SearchAxis axis) {
  switch (axis) {
    case SearchAxis::kX:
      return kapfix::v1::AXIS_X;
    case SearchAxis::kY:
      return kapfix::v1::AXIS_Y;
    case SearchAxis::kBoth:
      return kapfix::v1::AXIS_BOTH;
  }
  return kapfix::v1::AXIS_UNSPECIFIED;
}

kapfix::v1::Channel ToProto(ColorChannel channel) {
  return channel == ColorChannel::kRgbSum ? kapfix::v1::CHANNEL_RGB_SUM : kapfix::v1::CHANNEL_GREEN;
}

void ApplySearch(const kapfix::v1::SearchSettings& s, SearchConfig* c) {
  if (s.has_strategy()) c->strategy = s.strategy();
  switch (s.sampling()) {
    case kapfix::v1::SAMPLING_ALL:
      c->sampling.kind = SamplingKind::kAll;
      break;
    case kapfix::v1::SAMPLING_STATIC:
      c->sampling.kind = SamplingKind::kStatic;
      break;
    case kapfix::v1::SAMPLING_RANDOM:
      c->sampling.kind = SamplingKind::kRandom;
      break;
    default:
      break;
  }
  if (s.has_random_fraction()) c->sampling.fraction = s.random_fraction();
  if (s.has_patch_size_px()) c->patch_px = static_cast<int>(s.patch_size_px());
  if (s.has_slice_count()) c->slices = static_cast<int>(s.slice_count());
  switch (s.axis()) {
    case kapfix::v1::AXIS_X:
      c->axis = SearchAxis::kX;
      break;
    case kapfix::v1::AXIS_Y:
      c->axis = SearchAxis::kY;
      break;
    case kapfix::v1::AXIS_BOTH:
      c->axis = SearchAxis::kBoth;
      break;
    default:
      break;
  }
  if (s.has_search_range_px()) c->range_px = static_cast<int>(s.search_range_px());
  if (s.has_subpixel()) c->subpixel = s.subpixel();
  if (s.channel() == kapfix::v1::CHANNEL_GREEN) c->channel = ColorChannel::kGreen;
  if (s.channel() == kapfix::v1::CHANNEL_RGB_SUM) c->channel = ColorChannel::kRgbSum;
  switch (s.slice_score()) {
    case kapfix::v1::SLICE_SCORE_KIND_DC:
      c->slice_score = SliceScoreKind::kDc;
      break;
    case kapfix::v1::SLICE_SCORE_KIND_DC_HYSTERESIS:
      c->slice_score = SliceScoreKind::kDcHysteresis;
      break;
    case kapfix::v1::SLICE_SCORE_KIND_FFT:
      c->slice_score = SliceScoreKind::kFft;
      break;
    case kapfix::v1::SLICE_SCORE_KIND_SINGLE_SHOT:
      c->slice_score = SliceScoreKind::kSingleShot;
      break;
    default:
      break;
  }
  if (s.has_dc_hysteresis_px()) c->dc_hysteresis_px = s.dc_hysteresis_px();
}

// A lens by name switches to that stored profile; optics with a name define or update that
// profile (its deg/px then follows from them until it is calibrated).
void ApplyLens(const kapfix::v1::LensProfile& l, AgentConfig* c) {
  const std::string name = l.has_name() ? l.name() : c->lens;
  auto profile = std::find_if(c->lenses.begin(), c->lenses.end(),
                              [&](const LensProfile& p) { return p.name == name; });
  if (profile == c->lenses.end()) {
    c->lenses.push_back(LensProfile{.name = name});
    profile = std::prev(c->lenses.end());
  }
  if (l.has_focal_length_mm() || l.has_pixel_pitch_um()) {
    if (l.has_focal_length_mm()) profile->focal_mm = l.focal_length_mm();
    if (l.has_pixel_pitch_um()) profile->pixel_pitch_um = l.pixel_pitch_um();
    profile->deg_per_px_pan = 0;
    profile->deg_per_px_tilt = 0;
  }
  c->lens = name;
}

}  // namespace

void FillSettings(const AgentConfig& config, kapfix::v1::AgentState* state) {
  *state->mutable_gains() = config.gains;

  kapfix::v1::SearchSettings* s = state->mutable_search();
  s->set_strategy(config.search.strategy);
  s->set_sampling(ToProto(config.search.sampling.kind));
  s->set_random_fraction(static_cast<float>(config.search.sampling.fraction));
  s->set_patch_size_px(static_cast<std::uint32_t>(config.search.patch_px));
  s->set_slice_count(static_cast<std::uint32_t>(config.search.slices));
  s->set_axis(ToProto(config.search.axis));
  s->set_search_range_px(static_cast<std::uint32_t>(config.search.range_px));
  s->set_subpixel(config.search.subpixel);
  s->set_channel(ToProto(config.search.channel));
  s->set_slice_score(ToProto(config.search.slice_score));
  s->set_dc_hysteresis_px(static_cast<float>(config.search.dc_hysteresis_px));

  kapfix::v1::CameraSettings* camera = state->mutable_camera();
  camera->set_gain_db(static_cast<float>(config.camera.gain_db.value_or(0)));
  camera->set_exposure_us(static_cast<float>(config.camera.exposure_us.value_or(0)));
  camera->set_auto_exposure(!config.camera.exposure_us.has_value());

  const LensProfile& lens = config.active_lens();
  kapfix::v1::LensProfile* l = state->mutable_lens();
  l->set_name(lens.name);
  l->set_focal_length_mm(static_cast<float>(lens.focal_mm));
  l->set_pixel_pitch_um(static_cast<float>(lens.pixel_pitch_um));

  state->set_photo_interval_s(static_cast<float>(config.photos.interval_s));
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
      ApplySearch(command.set_search(), &updated.search);
      break;
    case kapfix::v1::Command::kSetCamera: {
      const kapfix::v1::CameraSettings& c = command.set_camera();
      if (c.has_gain_db()) updated.camera.gain_db = c.gain_db();
      if (c.has_exposure_us()) updated.camera.exposure_us = c.exposure_us();
      if (c.has_auto_exposure() && c.auto_exposure()) updated.camera.exposure_us.reset();
      break;
    }
    case kapfix::v1::Command::kSetLens:
      ApplyLens(command.set_lens(), &updated);
      break;
    case kapfix::v1::Command::kSetVideo:
      kapfix::v1::MergeSettings(command.set_video(), &updated.video);
      break;
    case kapfix::v1::Command::kSetPhotoIntervalS:
      updated.photos.interval_s = command.set_photo_interval_s();
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
    case kapfix::v1::Command::kSetPhotoIntervalS:
    case kapfix::v1::Command::kSetPhoto:
      return true;
    default:
      return false;
  }
}

}  // namespace kapfix::agent
