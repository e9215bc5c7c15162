// StateKeeper: the settings and latest results as a station sees them; it keeps the last
// finished reports and publishes the state after every change.
#include "agent/commands/state_keeper.hpp"

#include <gtest/gtest.h>

#include "tests/agent/support/recording_stream_sink.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::RecordingStreamSink;

kapfix::v1::SliceReport SliceReport(std::uint32_t recommended, bool finished) {
  kapfix::v1::SliceReport report;
  report.set_recommended_slice(recommended);
  report.set_finished(finished);
  report.set_progress_done(finished ? 30 : 10);
  return report;
}

TEST(StateKeeperTest, NoSliceReportBeforeSspRan) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  EXPECT_FALSE(keeper.State().has_last_slice_report());
  EXPECT_FALSE(keeper.RepublishSliceReport());
  EXPECT_EQ(sink.size(), 0u);
}

TEST(StateKeeperTest, KeepsTheLastFinishedSliceReport) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  keeper.OnSliceReport(SliceReport(3, true));
  keeper.OnSliceReport(SliceReport(6, true));
  ASSERT_TRUE(keeper.State().has_last_slice_report());
  EXPECT_EQ(keeper.State().last_slice_report().recommended_slice(), 6u);
}

TEST(StateKeeperTest, ProgressReportsDoNotReplaceTheFinishedOne) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  keeper.OnSliceReport(SliceReport(3, true));
  keeper.OnSliceReport(SliceReport(0, false));  // a new SSP under way
  EXPECT_EQ(keeper.State().last_slice_report().recommended_slice(), 3u);
}

TEST(StateKeeperTest, EverySliceReportIsPublished) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  keeper.OnSliceReport(SliceReport(0, false));
  keeper.OnSliceReport(SliceReport(4, true));
  EXPECT_EQ(sink.Messages<kapfix::v1::SliceReport>().size(), 2u);
}

TEST(StateKeeperTest, RepublishSliceReportPublishesTheLastFinishedOneAgain) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  keeper.OnSliceReport(SliceReport(4, true));
  keeper.OnSliceReport(SliceReport(0, false));
  EXPECT_TRUE(keeper.RepublishSliceReport());
  const auto reports = sink.Messages<kapfix::v1::SliceReport>();
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_TRUE(reports.back().finished());
  EXPECT_EQ(reports.back().recommended_slice(), 4u);
}

TEST(StateKeeperTest, KeepsTheLastFinishedPssReport) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  kapfix::v1::PssReport report;
  report.set_recommended_patch_size_px(100);
  report.set_finished(true);
  keeper.OnPssReport(report);
  kapfix::v1::PssReport progress;
  keeper.OnPssReport(progress);
  EXPECT_EQ(keeper.State().last_pss_report().recommended_patch_size_px(), 100u);
  EXPECT_EQ(sink.Messages<kapfix::v1::PssReport>().size(), 2u);
}

TEST(StateKeeperTest, ModeChangeIsPublishedAsState) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  keeper.OnModeChanged(AgentMode::kFixate, 4);
  const auto states = sink.Messages<kapfix::v1::AgentState>();
  ASSERT_EQ(states.size(), 1u);
  EXPECT_EQ(states[0].mode(), kapfix::v1::MODE_FIXATE);
  EXPECT_EQ(states[0].slice(), 4u);
}

TEST(StateKeeperTest, SetSettingsPublishesTheNewState) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  AgentConfig settings;
  settings.controller.kp = 0.3;
  keeper.SetSettings(settings);
  EXPECT_DOUBLE_EQ(keeper.settings().controller.kp, 0.3);
  const auto states = sink.Messages<kapfix::v1::AgentState>();
  ASSERT_EQ(states.size(), 1u);
  EXPECT_FLOAT_EQ(states[0].gains().p(), 0.3F);
}

TEST(StateKeeperTest, StateCountsTheStoredPhotosAndSaysSimulated) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, [] { return std::uint64_t{12}; });
  const kapfix::v1::AgentState state = keeper.State();
  EXPECT_EQ(state.photos_stored(), 12u);
  EXPECT_TRUE(state.simulated());
  EXPECT_FALSE(state.agent_version().empty());
}

TEST(StateKeeperTest, FinishedCalibrationIsStoredInTheLensProfile) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile("default");
  report.set_finished(true);
  keeper.OnCalibrationReport(report, LensCalibration{0.05, 0.07});
  EXPECT_DOUBLE_EQ(keeper.settings().active_lens().DegPerPxPan(), 0.05);
  EXPECT_DOUBLE_EQ(keeper.settings().active_lens().DegPerPxTilt(), 0.07);
  EXPECT_TRUE(keeper.State().has_calibration());
}

// A lens given by its optics (as in resources/kite.json) and then calibrated must still make
// a valid configuration: otherwise every later settings command is refused.
TEST(StateKeeperTest, CalibratingALensGivenByItsOpticsKeepsTheSettingsValid) {
  AgentConfig config;
  config.lenses = {LensProfile{.name = "3.5mm", .focal_mm = 3.5, .pixel_pitch_um = 10.6}};
  config.lens = "3.5mm";
  RecordingStreamSink sink;
  StateKeeper keeper(config, sink, true, nullptr);
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile("3.5mm");
  report.set_finished(true);
  keeper.OnCalibrationReport(report, LensCalibration{0.15, 0.16});
  std::string error;
  EXPECT_TRUE(keeper.settings().IsValid(&error)) << error;
  EXPECT_DOUBLE_EQ(keeper.settings().active_lens().DegPerPxPan(), 0.15);
}

TEST(StateKeeperTest, UnusableCalibrationLeavesTheLensAsItWas) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile("default");
  report.set_finished(true);
  keeper.OnCalibrationReport(report, std::nullopt);
  EXPECT_DOUBLE_EQ(keeper.settings().active_lens().DegPerPxPan(), 0.1);
}

}  // namespace
}  // namespace kapfix::agent
