#include "agent/server/command_validator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace kapfix::agent {
namespace {

using kapfix::v1::Command;
using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

kapfix::v1::AgentState State640x480() {
  kapfix::v1::AgentState state;
  state.set_frame_width_px(640);
  state.set_frame_height_px(480);
  state.mutable_search()->set_slice_count(9);
  return state;
}

kapfix::v1::Reply Check(const Command& command) {
  return CommandValidator().Validate(command, State640x480());
}

// Expects an OUT_OF_RANGE refusal whose reason contains every fragment.
template <typename... Fragments>
void ExpectOutOfRange(const Command& command, const Fragments&... fragments) {
  const auto reply = Check(command);
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
  EXPECT_THAT(reply.reason(), AllOf(HasSubstr(fragments)...));
}

Command Gains(float p) {
  Command command;
  command.mutable_set_gains()->set_p(p);
  return command;
}

// The command path takes a snapshot of the agent's state only when Validate reads it: the
// frame size caps the search settings, the photo window is bounded by its cap, select_slice
// needs the slice count; gains, camera, lens, video and request_state read nothing of it.
TEST(CommandValidatorNeedsStateTest, OnlyCommandsWhoseRangesDependOnTheStateNeedIt) {
  Command search;
  search.mutable_set_search();
  Command photo;
  photo.mutable_set_photo();
  Command slice;
  slice.set_select_slice(1);
  EXPECT_TRUE(CommandValidator::NeedsState(search));
  EXPECT_TRUE(CommandValidator::NeedsState(photo));
  EXPECT_TRUE(CommandValidator::NeedsState(slice));
  Command other;
  other.mutable_request_state();
  EXPECT_FALSE(CommandValidator::NeedsState(other));
  other.mutable_set_gains();
  EXPECT_FALSE(CommandValidator::NeedsState(other));
  other.mutable_set_camera();
  EXPECT_FALSE(CommandValidator::NeedsState(other));
  other.mutable_set_lens();
  EXPECT_FALSE(CommandValidator::NeedsState(other));
  EXPECT_FALSE(CommandValidator::NeedsState(Command()));
}

TEST(CommandValidatorGainsTest, AcceptsAPartialUpdateInRange) {
  Command command;
  command.mutable_set_gains()->set_p(0.8F);
  command.mutable_set_gains()->set_dead_band_px(1.5F);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorGainsTest, RefusesNaNNamingTheFieldAndTheLimit) {
  ExpectOutOfRange(Gains(kNaN), "set_gains.p = nan", "finite", "[0.01, 10]");
}

TEST(CommandValidatorGainsTest, RefusesInfinity) {
  Command command;
  command.mutable_set_gains()->set_i(kInf);
  ExpectOutOfRange(command, "set_gains.i = inf", "[0, 10] 1/s");
}

TEST(CommandValidatorGainsTest, RefusesANegativeGain) {
  Command command;
  command.mutable_set_gains()->set_d(-0.1F);
  ExpectOutOfRange(command, "set_gains.d = -0.1", "[0, 10]");
}

TEST(CommandValidatorGainsTest, RefusesAGainAboveItsLimit) {
  ExpectOutOfRange(Gains(10.5F), "set_gains.p = 10.5");
}

TEST(CommandValidatorGainsTest, RefusesAZeroRateLimit) {
  Command command;
  command.mutable_set_gains()->set_rate_limit_deg_per_s(0);
  ExpectOutOfRange(command, "set_gains.rate_limit_deg_per_s = 0", "[1, 1000] deg/s");
}

// Issue 15: a tiny positive rate froze the servos while passing a "> 0" check.
TEST(CommandValidatorGainsTest, RefusesATinyRateLimit) {
  Command command;
  command.mutable_set_gains()->set_rate_limit_deg_per_s(1e-45F);
  ExpectOutOfRange(command, "set_gains.rate_limit_deg_per_s = 1e-45", "[1, 1000] deg/s");
}

// The config check refuses kp = 0 and ki > 10: the command check must refuse the same.
TEST(CommandValidatorGainsTest, RefusesAZeroProportionalGain) {
  ExpectOutOfRange(Gains(0), "set_gains.p = 0", "[0.01, 10]");
}

TEST(CommandValidatorGainsTest, RefusesAnIntegralGainAboveTheConfigsLimit) {
  Command command;
  command.mutable_set_gains()->set_i(11);
  ExpectOutOfRange(command, "set_gains.i = 11", "[0, 10] 1/s");
}

TEST(CommandValidatorGainsTest, RefusesAnUnknownControllerValue) {
  Command command;
  command.mutable_set_gains()->set_controller(static_cast<kapfix::v1::ControllerKind>(99));
  ExpectOutOfRange(command, "set_gains.controller = 99", "unknown value", "CONTROLLER_KIND_PID");
}

TEST(CommandValidatorGainsTest, OneBadFieldRefusesTheWholeCommand) {
  Command command = Gains(0.5F);
  command.mutable_set_gains()->set_dead_band_px(kNaN);
  ExpectOutOfRange(command, "set_gains.dead_band_px");
}

TEST(CommandValidatorSearchTest, AcceptsAKnownStrategyAndFittingPatch) {
  Command command;
  command.mutable_set_search()->set_strategy("pyr");
  command.mutable_set_search()->set_patch_size_px(480);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorSearchTest, RefusesAnUnknownStrategyListingTheKnownOnes) {
  Command command;
  command.mutable_set_search()->set_strategy("h99");
  ExpectOutOfRange(command, "set_search.strategy = 'h99'", "h23", "pyr");
}

TEST(CommandValidatorSearchTest, RefusesAPatchLargerThanTheFrame) {
  Command command;
  command.mutable_set_search()->set_patch_size_px(481);
  ExpectOutOfRange(command, "set_search.patch_size_px = 481", "[8, 480]", "fit in the frame");
}

TEST(CommandValidatorSearchTest, RefusesATinyPatch) {
  Command command;
  command.mutable_set_search()->set_patch_size_px(4);
  ExpectOutOfRange(command, "set_search.patch_size_px = 4");
}

TEST(CommandValidatorSearchTest, RefusesZeroSlices) {
  Command command;
  command.mutable_set_search()->set_slice_count(0);
  ExpectOutOfRange(command, "set_search.slice_count = 0", "[1, 64]");
}

TEST(CommandValidatorSearchTest, RefusesARandomFractionOfZero) {
  Command command;
  command.mutable_set_search()->set_random_fraction(0);
  ExpectOutOfRange(command, "set_search.random_fraction = 0", "[0.01, 1]");
}

TEST(CommandValidatorSearchTest, RefusesATinyRandomFraction) {
  Command command;
  command.mutable_set_search()->set_random_fraction(1e-45F);
  ExpectOutOfRange(command, "set_search.random_fraction = 1e-45", "[0.01, 1]");
}

TEST(CommandValidatorSearchTest, RefusesAnUnknownAxis) {
  Command command;
  command.mutable_set_search()->set_axis(static_cast<kapfix::v1::Axis>(7));
  ExpectOutOfRange(command, "set_search.axis = 7", "AXIS_BOTH");
}

TEST(CommandValidatorSearchTest, RefusesAnUnknownSampling) {
  Command command;
  command.mutable_set_search()->set_sampling(static_cast<kapfix::v1::Sampling>(-1));
  ExpectOutOfRange(command, "set_search.sampling = -1");
}

TEST(CommandValidatorSearchTest, RefusesASearchRangeBeyondTheFrame) {
  Command command;
  command.mutable_set_search()->set_search_range_px(641);
  ExpectOutOfRange(command, "set_search.search_range_px = 641", "[1, 640]");
}

TEST(CommandValidatorSearchTest, RefusesANaNHysteresis) {
  Command command;
  command.mutable_set_search()->set_dc_hysteresis_px(kNaN);
  ExpectOutOfRange(command, "set_search.dc_hysteresis_px = nan");
}

TEST(CommandValidatorSliceTest, AcceptsTheLastSlice) {
  Command command;
  command.set_select_slice(9);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorSliceTest, RefusesSliceZero) {
  Command command;
  command.set_select_slice(0);
  ExpectOutOfRange(command, "select_slice = 0", "[1, 9]");
}

TEST(CommandValidatorSliceTest, RefusesASliceBeyondTheAgentsSliceCount) {
  Command command;
  command.set_select_slice(10);
  ExpectOutOfRange(command, "select_slice = 10", "[1, 9]");
}

TEST(CommandValidatorCameraTest, RefusesANegativeExposure) {
  Command command;
  command.mutable_set_camera()->set_exposure_us(-100);
  ExpectOutOfRange(command, "set_camera.exposure_us = -100", "[10, 1e+07] µs");
}

TEST(CommandValidatorCameraTest, RefusesANaNGain) {
  Command command;
  command.mutable_set_camera()->set_gain_db(kNaN);
  ExpectOutOfRange(command, "set_camera.gain_db = nan", "[0, 48] dB");
}

TEST(CommandValidatorCameraTest, AcceptsAutoExposureAlone) {
  Command command;
  command.mutable_set_camera()->set_auto_exposure(true);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorLensTest, RefusesANameThatIsAPath) {
  Command command;
  command.mutable_set_lens()->set_name("../../etc/passwd");
  ExpectOutOfRange(command, "set_lens.name", "not starting with '.'");
}

TEST(CommandValidatorLensTest, RefusesANameWithASlash) {
  Command command;
  command.mutable_set_lens()->set_name("a/b");
  ExpectOutOfRange(command, "set_lens.name = 'a/b'");
}

TEST(CommandValidatorLensTest, RefusesAZeroPixelPitch) {
  Command command;
  command.mutable_set_lens()->set_name("6mm");
  command.mutable_set_lens()->set_pixel_pitch_um(0);
  ExpectOutOfRange(command, "set_lens.pixel_pitch_um = 0");
}

TEST(CommandValidatorLensTest, AcceptsAProfileByItsOptics) {
  Command command;
  command.mutable_set_lens()->set_name("3.5mm");
  command.mutable_set_lens()->set_focal_length_mm(3.5F);
  command.mutable_set_lens()->set_pixel_pitch_um(4.4F);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorPhotoTest, AcceptsIntervalZeroAsOff) {
  Command command;
  command.mutable_set_photo()->set_interval_s(0);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorPhotoTest, RefusesANegativeInterval) {
  Command command;
  command.mutable_set_photo()->set_interval_s(-5);
  ExpectOutOfRange(command, "set_photo.interval_s = -5", "0 (off)", "[0.5, 86400]");
}

TEST(CommandValidatorPhotoTest, RefusesANaNInterval) {
  Command command;
  command.mutable_set_photo()->set_interval_s(kNaN);
  ExpectOutOfRange(command, "set_photo.interval_s = nan");
}

TEST(CommandValidatorPhotoTest, RefusesAnOverlongNote) {
  Command command;
  command.mutable_take_photo()->set_note(std::string(2000, 'n'));
  ExpectOutOfRange(command, "take_photo.note is 2000 bytes", "1024");
}

// Issue 13: set_photo's window may not outlast its cap, given in the command or the agent's.
TEST(CommandValidatorPhotoTest, RefusesAWindowLongerThanTheCapInTheCommand) {
  Command command;
  command.mutable_set_photo()->set_window_s(5.0F);
  command.mutable_set_photo()->set_window_cap_s(3.0F);
  ExpectOutOfRange(command, "set_photo.window_s = 5", "more than window_cap_s = 3");
}

// The bound comes from the schema (window_s's `at_most`), and so does the cap of an agent that
// has not said its own yet (window_cap_s's initial value, 10 s).
TEST(CommandValidatorPhotoTest, AnAgentWithoutACapIsHeldToTheSchemasInitialCap) {
  Command command;
  command.mutable_set_photo()->set_window_s(11.0F);
  const auto reply = CommandValidator().Validate(command, State640x480());
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.reason(),
            "set_photo.window_s = 11 s is more than window_cap_s = 10 s: shorten the window or "
            "raise the cap");
  command.mutable_set_photo()->set_window_s(9.5F);
  EXPECT_TRUE(CommandValidator().Validate(command, State640x480()).ok());
}

TEST(CommandValidatorPhotoTest, RefusesAWindowLongerThanTheAgentsCap) {
  Command command;
  command.mutable_set_photo()->set_window_s(5.0F);
  kapfix::v1::AgentState state = State640x480();
  state.mutable_photo()->set_window_cap_s(4.0F);
  const auto reply = CommandValidator().Validate(command, state);
  EXPECT_FALSE(reply.ok());
  EXPECT_THAT(reply.reason(), HasSubstr("more than window_cap_s = 4"));
  state.mutable_photo()->set_window_cap_s(6.0F);
  EXPECT_TRUE(CommandValidator().Validate(command, state).ok());
}

TEST(CommandValidatorPhotoTest, RefusesAnExposureThatIsNotPositive) {
  Command command;
  command.mutable_set_photo()->set_exposure_ms(0.0F);
  ExpectOutOfRange(command, "set_photo.exposure_ms = 0");
  command.mutable_set_photo()->set_exposure_ms(-1.0F);
  ExpectOutOfRange(command, "set_photo.exposure_ms = -1");
}

TEST(CommandValidatorPhotoTest, AcceptsBestPhaseWithAWindowWithinTheCap) {
  Command command;
  command.mutable_set_photo()->set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  command.mutable_set_photo()->set_window_s(2.0F);
  EXPECT_TRUE(Check(command).ok()) << Check(command).reason();
}

TEST(CommandValidatorVideoTest, AcceptsFpsZeroAsVideoOff) {
  Command command;
  command.mutable_set_video()->set_fps(0);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorVideoTest, RefusesNegativeFps) {
  Command command;
  command.mutable_set_video()->set_fps(-1);
  ExpectOutOfRange(command, "set_video.fps = -1", "0 (off) or [0.1, 60] fps");
}

TEST(CommandValidatorVideoTest, RefusesJpegQualityZero) {
  Command command;
  command.mutable_set_video()->set_jpeg_quality(0);
  ExpectOutOfRange(command, "set_video.jpeg_quality = 0", "[10, 100]");
}

TEST(CommandValidatorVideoTest, RefusesJpegQualityAbove100) {
  Command command;
  command.mutable_set_video()->set_jpeg_quality(101);
  ExpectOutOfRange(command, "set_video.jpeg_quality = 101");
}

TEST(CommandValidatorVideoTest, RefusesAScaleAboveOne) {
  Command command;
  command.mutable_set_video()->set_scale(1.5F);
  ExpectOutOfRange(command, "set_video.scale = 1.5", "[0.05, 1]");
}

TEST(CommandValidatorVideoTest, RefusesATinyScale) {
  Command command;
  command.mutable_set_video()->set_scale(0.001F);
  ExpectOutOfRange(command, "set_video.scale = 0.001", "[0.05, 1]");
}

TEST(CommandValidatorModeTest, AcceptsSspWithADeadline) {
  Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  command.mutable_set_mode()->set_deadline_frames(400);
  EXPECT_TRUE(Check(command).ok());
}

TEST(CommandValidatorModeTest, RefusesAnUnspecifiedMode) {
  Command command;
  command.mutable_set_mode();
  ExpectOutOfRange(command, "set_mode.mode = 0", "a value is required", "MODE_FIXATE");
}

TEST(CommandValidatorModeTest, RefusesAnUnknownMode) {
  Command command;
  command.mutable_set_mode()->set_mode(static_cast<kapfix::v1::Mode>(42));
  ExpectOutOfRange(command, "set_mode.mode = 42", "unknown value");
}

TEST(CommandValidatorModeTest, RefusesAnInfiniteDeadline) {
  Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_PSS);
  command.mutable_set_mode()->set_deadline_s(kInf);
  ExpectOutOfRange(command, "set_mode.deadline_s = inf");
}

TEST(CommandValidatorModeTest, RefusesAZeroFrameDeadline) {
  Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  command.mutable_set_mode()->set_deadline_frames(0);
  ExpectOutOfRange(command, "set_mode.deadline_frames = 0");
}

TEST(CommandValidatorRequestStateTest, RefusesANegativeResendTime) {
  Command command;
  command.mutable_request_state()->set_resend_photos_since_us(-1);
  ExpectOutOfRange(command, "request_state.resend_photos_since_us = -1");
}

TEST(CommandValidatorUnknownTest, RefusesACommandWithNoCommandField) {
  const auto reply = Check(Command());
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND);
  EXPECT_THAT(reply.reason(), HasSubstr("no command field"));
}

TEST(CommandValidatorUnknownTest, NamesTheFieldNumberOfACommandFromANewerStation) {
  // Field 99, varint 1: what a newer station's command this build does not know looks like.
  Command command;
  ASSERT_TRUE(command.ParseFromString(std::string("\x98\x06\x01", 3)));
  const auto reply = Check(command);
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND);
  EXPECT_THAT(reply.reason(), HasSubstr("field 99"));
  // The highest command field this agent knows, set_photo (12), not a number written by hand.
  EXPECT_THAT(reply.reason(), HasSubstr("up to field 12"));
}

TEST(CommandValidatorUnknownTest, SaysARemovedFieldOfAnOlderStationWasRemoved) {
  // Field 9, a float: the photo interval an older station sends as set_photo_interval_s.
  Command command;
  ASSERT_TRUE(command.ParseFromString(std::string("\x4d\x00\x00\xa0\x40", 5)));
  const auto reply = Check(command);
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND);
  EXPECT_THAT(reply.reason(), HasSubstr("field 9 was removed"));
}

TEST(CommandValidatorLimitsTest, UsesTheFallbackFrameSizeWhenTheStateHasNone) {
  Command command;
  command.mutable_set_search()->set_patch_size_px(1601);
  const auto reply = CommandValidator().Validate(command, kapfix::v1::AgentState());
  EXPECT_THAT(reply.reason(), HasSubstr("[8, 1600]"));
}

}  // namespace
}  // namespace kapfix::agent
