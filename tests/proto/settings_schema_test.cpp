// The settings schema: ranges, units and help read from the fields' options.
#include "kapfix/v1/settings_schema.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <set>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings.pb.h"

namespace kapfix::v1 {
namespace {

using ::testing::HasSubstr;

const SettingOptions& Of(const google::protobuf::Descriptor& message, const char* field) {
  const auto* found = SettingField(message, field);
  EXPECT_NE(found, nullptr) << field;
  return *SettingOf(*found);
}

TEST(SettingsSchemaTest, ARangeReadsWithItsUnitOnce) {
  EXPECT_EQ(RangeText(Of(*Gains::descriptor(), "rate_limit_deg_per_s")), "[1, 1000] deg/s");
}

TEST(SettingsSchemaTest, ARatioShowsNoUnit) {
  EXPECT_EQ(RangeText(Of(*Gains::descriptor(), "p")), "[0.01, 10]");
}

TEST(SettingsSchemaTest, ZeroMeansOffIsPartOfTheRange) {
  const SettingOptions& interval = Of(*PhotoSettings::descriptor(), "interval_s");
  EXPECT_EQ(RangeText(interval), "0 (off) or [0.5, 86400] s");
  EXPECT_TRUE(InRange(0, interval));
  EXPECT_FALSE(InRange(0.1, interval));
}

TEST(SettingsSchemaTest, NaNIsNeverInRange) {
  EXPECT_FALSE(InRange(std::nan(""), Of(*Gains::descriptor(), "i")));
}

TEST(SettingsSchemaTest, TheReasonShowsATinyFloatAsTheOperatorTypedIt) {
  EXPECT_EQ(OutOfRangeReason("rate", 1e-45F, Of(*Gains::descriptor(), "rate_limit_deg_per_s")),
            "rate = 1e-45: must be in [1, 1000] deg/s");
}

TEST(SettingsSchemaTest, CheckSettingsNamesTheFirstBadFieldWithItsPrefix) {
  Gains gains;
  gains.set_p(0.5F);
  gains.set_dead_band_px(-1);
  EXPECT_EQ(CheckSettings(gains, "set_gains"),
            "set_gains.dead_band_px = -1: must be in [0, 50] px");
}

TEST(SettingsSchemaTest, CheckSettingsIgnoresAbsentFields) {
  EXPECT_EQ(CheckSettings(Gains(), "set_gains"), "");
}

TEST(SettingsSchemaTest, CheckSettingsRefusesAnUnknownEnumValue) {
  SearchSettings search;
  search.set_axis(static_cast<Axis>(9));
  EXPECT_THAT(CheckSettings(search, "s"), HasSubstr("s.axis = 9: unknown value"));
}

TEST(SettingsSchemaTest, AFieldThatIsNoSettingIsReportedAsABug) {
  EXPECT_THAT(CheckSetting(*Gains::descriptor(), "no_such", 1, "x"), HasSubstr("a bug"));
}

TEST(SettingsSchemaTest, EnumWordsDropTheEnumPrefix) {
  EXPECT_EQ(SettingWord(*ControllerKind_descriptor()->FindValueByNumber(CONTROLLER_KIND_PID)),
            "pid");
  EXPECT_EQ(
      SettingWord(*SliceScoreKind_descriptor()->FindValueByNumber(SLICE_SCORE_KIND_DC_HYSTERESIS)),
      "dc_hysteresis");
  EXPECT_EQ(SettingWord(*Channel_descriptor()->FindValueByNumber(CHANNEL_RGB_SUM)), "rgb-sum");
}

// Issue 15: a lower bound is either 0 itself (no dead band, no integral term) or a value at
// which the setting still works, never "just above zero" (a rate limit of 1e-45 deg/s).
TEST(SettingsSchemaTest, EveryNumericSettingHasAMeaningfulLowerBound) {
  for (const SettingEntry& entry : SettingEntries()) {
    const auto type = entry.field->cpp_type();
    if (type != google::protobuf::FieldDescriptor::CPPTYPE_FLOAT &&
        type != google::protobuf::FieldDescriptor::CPPTYPE_UINT32) {
      continue;
    }
    const SettingOptions& o = *entry.options;
    EXPECT_LT(o.min(), o.max()) << entry.field->full_name();
    EXPECT_TRUE(o.min() == 0 || o.min() >= 0.01) << entry.field->full_name() << ": " << o.min();
    EXPECT_FALSE(o.help().empty()) << entry.field->full_name();
  }
}

TEST(SettingsSchemaTest, SettingsWhereZeroStopsTheLoopRefuseATinyValue) {
  EXPECT_FALSE(InRange(1e-45, Of(*Gains::descriptor(), "rate_limit_deg_per_s")));
  EXPECT_FALSE(InRange(1e-45, Of(*SearchSettings::descriptor(), "random_fraction")));
  EXPECT_FALSE(InRange(0.001, Of(*VideoSettings::descriptor(), "scale")));
  EXPECT_FALSE(InRange(1e-45, Of(*VideoSettings::descriptor(), "fps")));
}

TEST(SettingsSchemaTest, EveryKeyIsUnique) {
  std::set<std::string> keys;
  for (const SettingEntry& entry : SettingEntries()) {
    EXPECT_TRUE(keys.insert(entry.options->key()).second) << entry.options->key();
  }
  EXPECT_GE(keys.size(), 27u);  // every key kapfix-ctl had before the schema
}

TEST(SettingsSchemaTest, EveryInitialValueParsesAndIsInItsRange) {
  for (const SettingEntry& entry : SettingEntries()) {
    if (entry.command_field == entry.field) continue;  // a scalar command: no message to fill
    std::unique_ptr<google::protobuf::Message> settings(
        google::protobuf::MessageFactory::generated_factory()
            ->GetPrototype(entry.field->containing_type())
            ->New());
    std::string error;
    EXPECT_TRUE(SetInitialSettings(settings.get(), &error)) << error;
    EXPECT_EQ(CheckSettings(*settings, ""), "") << entry.field->full_name();
  }
}

TEST(SettingsSchemaTest, InitialSettingsSetEveryFieldThatHasAnInitialValue) {
  const Gains gains = InitialSettings<Gains>();
  EXPECT_EQ(gains.controller(), CONTROLLER_KIND_PREDICTIVE);
  EXPECT_TRUE(gains.has_p());
  EXPECT_FLOAT_EQ(gains.rate_limit_deg_per_s(), 90);
  // A field without one stays absent (its group's defaults live in the agent's config).
  EXPECT_FALSE(InitialSettings<CameraSettings>().has_gain_db());
}

TEST(SettingsSchemaTest, MergeSettingsReplacesWhatIsPresentAndKeepsAnUnspecifiedEnum) {
  Gains held = InitialSettings<Gains>();
  Gains update;
  update.set_p(0.3F);
  update.set_controller(CONTROLLER_KIND_UNSPECIFIED);
  MergeSettings(update, &held);
  EXPECT_FLOAT_EQ(held.p(), 0.3F);
  EXPECT_EQ(held.controller(), CONTROLLER_KIND_PREDICTIVE);
  EXPECT_FLOAT_EQ(held.dead_band_px(), 0.5F);  // absent: kept
  PhotoSettings photo = InitialSettings<PhotoSettings>();
  PhotoSettings unspecified;
  unspecified.set_camera(PHOTO_CAMERA_UNSPECIFIED);  // present, but "unchanged"
  MergeSettings(unspecified, &photo);
  EXPECT_EQ(photo.camera(), PHOTO_CAMERA_AGENT);
}

TEST(SettingsSchemaTest, AnEnumWordReadsBothWays) {
  EXPECT_EQ(WordOf(CONTROLLER_KIND_PID), "pid");
  EXPECT_EQ(WordOf(SHUTTER_BEST_PHASE), "best-phase");
  EXPECT_EQ(WordOf(CONTROLLER_KIND_UNSPECIFIED), "");
  EXPECT_EQ(ValueOfWord(*ControllerKind_descriptor(), "predictive")->number(),
            CONTROLLER_KIND_PREDICTIVE);
  EXPECT_EQ(ValueOfWord(*ControllerKind_descriptor(), "bang-bang"), nullptr);
  EXPECT_EQ(ValueOfWord(*ControllerKind_descriptor(), ""), nullptr);
}

}  // namespace
}  // namespace kapfix::v1
