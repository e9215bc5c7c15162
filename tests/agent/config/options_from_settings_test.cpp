// A settings message copied into common/'s options by field name (issue 11).
#include "agent/config/options_from_settings.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>

#include "agent/config/lens_profile.hpp"
#include "agent/config/search_config.hpp"
#include "common/control/controller.hpp"
#include "common/shutter/best_phase_shutter.hpp"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

// The names an options struct lists, whatever their members' types.
struct NameCollector {
  std::set<std::string> names;
  template <typename T>
  void operator()(std::string_view name, T& /*member*/) {
    names.emplace(name);
  }
  template <typename T, typename Parse>
  void operator()(std::string_view name, T& /*member*/, Parse /*parse*/) {
    names.emplace(name);
  }
};

// Every setting of `settings` but `elsewhere` is one of `options`' fields, and the types agree:
// a new proto field the options struct does not take fails here.
template <typename Options>
void ExpectEverySettingHasACounterpart(const google::protobuf::Message& settings,
                                       const std::set<std::string>& elsewhere) {
  Options options;
  NameCollector collector;
  options.VisitFields(collector);
  const google::protobuf::Descriptor& type = *settings.GetDescriptor();
  for (int i = 0; i < type.field_count(); ++i) {
    const std::string& name = type.field(i)->name();
    if (kapfix::v1::SettingOf(*type.field(i)) == nullptr || elsewhere.count(name) != 0) continue;
    EXPECT_EQ(collector.names.count(name), 1U) << type.full_name() << "." << name;
  }
  std::string error;
  EXPECT_TRUE(CopySettings(settings, &options, &error)) << error;
}

TEST(OptionsFromSettingsTest, EveryGainIsAControllerGainsField) {
  // `controller` picks the controller's class (MakeController), it is no gain.
  ExpectEverySettingHasACounterpart<ControllerGains>(kapfix::v1::Gains(), {"controller"});
}

TEST(OptionsFromSettingsTest, EveryPhotoSettingIsAShutterOptionsField) {
  // `camera` picks which camera takes the photo (PhotoCameras), `interval_s` when the photo
  // taker asks for one: neither is how the shutter times it.
  ExpectEverySettingHasACounterpart<BestPhaseShutterOptions>(
      kapfix::v1::InitialSettings<kapfix::v1::PhotoSettings>(), {"camera", "interval_s"});
}

TEST(OptionsFromSettingsTest, EverySearchSettingIsASearchConfigField) {
  kapfix::v1::SearchSettings search =
      SettingsFromOptions<kapfix::v1::SearchSettings>(SearchConfig{});
  ExpectEverySettingHasACounterpart<SearchConfig>(search, {});
}

TEST(OptionsFromSettingsTest, EveryLensSettingIsALensProfileField) {
  ExpectEverySettingHasACounterpart<LensProfile>(kapfix::v1::LensProfile(), {});
}

TEST(OptionsFromSettingsTest, SearchSettingsGoToTheMessageAndBackUnchanged) {
  SearchConfig search;
  search.strategy = "h21";
  search.sampling.kind = SamplingKind::kStatic;
  search.sampling.fraction = 0.25;
  search.patch_px = 64;
  search.slices = 5;
  search.axis = SearchAxis::kBoth;
  search.range_px = 40;
  search.subpixel = false;
  search.channel = ColorChannel::kRgbSum;
  search.score = SliceScoreKind::kDcHysteresis;
  search.hysteresis_px = 2.5;
  const auto message = SettingsFromOptions<kapfix::v1::SearchSettings>(search);
  EXPECT_EQ(message.patch_size_px(), 64U);
  EXPECT_EQ(message.slice_score(), kapfix::v1::SLICE_SCORE_KIND_DC_HYSTERESIS);
  EXPECT_EQ(message.channel(), kapfix::v1::CHANNEL_RGB_SUM);
  EXPECT_EQ(message.sampling(), kapfix::v1::SAMPLING_STATIC);
  const SearchConfig back = OptionsFromSettings<SearchConfig>(message);
  EXPECT_EQ(back.strategy, "h21");
  EXPECT_EQ(back.sampling.kind, SamplingKind::kStatic);
  EXPECT_DOUBLE_EQ(back.sampling.fraction, 0.25);
  EXPECT_EQ(back.patch_px, 64);
  EXPECT_EQ(back.slices, 5);
  EXPECT_EQ(back.axis, SearchAxis::kBoth);
  EXPECT_EQ(back.range_px, 40);
  EXPECT_FALSE(back.subpixel);
  EXPECT_EQ(back.channel, ColorChannel::kRgbSum);
  EXPECT_EQ(back.score, SliceScoreKind::kDcHysteresis);
  EXPECT_DOUBLE_EQ(back.hysteresis_px, 2.5);
}

TEST(OptionsFromSettingsTest, EverySliceScoreWordIsASliceScoreKind) {
  const google::protobuf::EnumDescriptor& kinds = *kapfix::v1::SliceScoreKind_descriptor();
  for (int i = 0; i < kinds.value_count(); ++i) {
    if (kinds.value(i)->number() == 0) continue;  // unspecified: "unchanged", never held
    kapfix::v1::SearchSettings search =
        SettingsFromOptions<kapfix::v1::SearchSettings>(SearchConfig{});
    search.set_slice_score(static_cast<kapfix::v1::SliceScoreKind>(kinds.value(i)->number()));
    SearchConfig config;
    std::string error;
    EXPECT_TRUE(CopySettings(search, &config, &error)) << error;
  }
}

TEST(OptionsFromSettingsTest, ANegativeCountIsRefusedWhenWrittenToTheMessage) {
  SearchConfig search;
  search.patch_px = -5;
  kapfix::v1::SearchSettings message;
  std::string error;
  EXPECT_FALSE(WriteSettings(search, &message, &error));
  EXPECT_EQ(error, "kapfix.v1.SearchSettings.patch_size_px = -5: must be ≥ 0");
  EXPECT_THROW(SettingsFromOptions<kapfix::v1::SearchSettings>(search), std::logic_error);
}

TEST(OptionsFromSettingsTest, AnEnumValueWithoutASettingWordIsRefusedWhenWritten) {
  SearchConfig search;
  search.channel = ColorChannel::kRgb;  // common/'s per-channel SSD: no setting offers it
  kapfix::v1::SearchSettings message;
  std::string error;
  EXPECT_FALSE(WriteSettings(search, &message, &error));
  EXPECT_EQ(error, "kapfix.v1.SearchSettings.channel: the options' value has no setting word");
}

TEST(OptionsFromSettingsTest, EveryShutterWordIsAShutterMode) {
  const google::protobuf::EnumDescriptor& shutter = *kapfix::v1::Shutter_descriptor();
  for (int i = 0; i < shutter.value_count(); ++i) {
    if (shutter.value(i)->number() == 0) continue;  // unspecified: "unchanged", never held
    kapfix::v1::PhotoSettings photo = kapfix::v1::InitialSettings<kapfix::v1::PhotoSettings>();
    photo.set_shutter(static_cast<kapfix::v1::Shutter>(shutter.value(i)->number()));
    BestPhaseShutterOptions options;
    std::string error;
    EXPECT_TRUE(CopySettings(photo, &options, &error)) << error;
  }
  kapfix::v1::PhotoSettings photo = kapfix::v1::InitialSettings<kapfix::v1::PhotoSettings>();
  photo.set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_EQ(OptionsFromSettings<BestPhaseShutterOptions>(photo).mode, ShutterMode::kBestPhase);
}

TEST(OptionsFromSettingsTest, AnUnsetEnumIsRefusedNamingIt) {
  kapfix::v1::PhotoSettings photo = kapfix::v1::InitialSettings<kapfix::v1::PhotoSettings>();
  photo.clear_shutter();
  BestPhaseShutterOptions options;
  std::string error;
  EXPECT_FALSE(CopySettings(photo, &options, &error));
  EXPECT_EQ(error, "kapfix.v1.PhotoSettings.shutter: not set");
}

TEST(OptionsFromSettingsTest, CopiesEachValueByNameAndKeepsTheRest) {
  kapfix::v1::Gains gains;
  gains.set_p(0.25F);
  gains.set_i(0.5F);
  gains.set_d(2);
  gains.set_dead_band_px(3);
  gains.set_rate_limit_deg_per_s(45);
  ControllerGains base;
  base.integral_limit_px = 7;  // no setting: stays as given
  const ControllerGains copied = OptionsFromSettings(gains, base);
  EXPECT_DOUBLE_EQ(copied.p, 0.25);
  EXPECT_DOUBLE_EQ(copied.i, 0.5);
  EXPECT_DOUBLE_EQ(copied.d, 2);
  EXPECT_DOUBLE_EQ(copied.dead_band_px, 3);
  EXPECT_DOUBLE_EQ(copied.rate_limit_deg_per_s, 45);
  EXPECT_DOUBLE_EQ(copied.integral_limit_px, 7);
}

struct MisnamedOptions {
  double gain = 0;
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("gain", gain);
  }
};

TEST(OptionsFromSettingsTest, ANameTheMessageLacksIsRefusedNamingIt) {
  MisnamedOptions options;
  std::string error;
  EXPECT_FALSE(CopySettings(kapfix::v1::Gains(), &options, &error));
  EXPECT_EQ(error, "kapfix.v1.Gains.gain: no such field, but the options struct lists it");
}

struct MistypedOptions {
  bool p = false;
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("p", p);
  }
};

TEST(OptionsFromSettingsTest, ATypeTheMemberCannotHoldIsRefusedNamingIt) {
  MistypedOptions options;
  std::string error;
  EXPECT_FALSE(CopySettings(kapfix::v1::Gains(), &options, &error));
  EXPECT_EQ(error, "kapfix.v1.Gains.p: a float cannot be copied into a bool member");
  EXPECT_THROW(OptionsFromSettings<MistypedOptions>(kapfix::v1::Gains()), std::logic_error);
}

struct CountOptions {
  int count = 0;
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("slice_count", count);
  }
};

TEST(OptionsFromSettingsTest, AWholeNumberBeyondAnIntIsRefused) {
  kapfix::v1::SearchSettings search;
  search.set_slice_count(3'000'000'000U);
  CountOptions options;
  std::string error;
  EXPECT_FALSE(CopySettings(search, &options, &error));
  EXPECT_EQ(error, "kapfix.v1.SearchSettings.slice_count = 3000000000: too large for an int");
  search.set_slice_count(9);
  EXPECT_TRUE(CopySettings(search, &options, &error)) << error;
  EXPECT_EQ(options.count, 9);
}

}  // namespace
}  // namespace kapfix::agent
