// StateKeeper: the settings and latest results as a station sees them; it keeps the last
// finished reports and publishes the state after every change.
#include "agent/commands/state_keeper.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <thread>

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

// Issue 10: a device coming or going is a new state, published at once; the same health
// again (a retry that failed again, every frame) is not.
TEST(StateKeeperTest, ADeviceHealthChangeIsPublishedOnceAsANewState) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, false, nullptr);
  const std::uint64_t version = keeper.State().version();
  DevicesHealth health;
  health.camera = DeviceHealth::Waiting("cannot open /dev/video0");
  keeper.OnDeviceHealth(health);
  keeper.OnDeviceHealth(health);
  health.camera = DeviceHealth::Ok();
  keeper.OnDeviceHealth(health);
  keeper.OnDeviceHealth(health);
  const auto states = sink.Messages<kapfix::v1::AgentState>();
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].camera_health().status(), kapfix::v1::DEVICE_WAITING);
  EXPECT_EQ(states[0].camera_health().reason(), "cannot open /dev/video0");
  EXPECT_EQ(states[0].servo_health().status(), kapfix::v1::DEVICE_OK);
  EXPECT_EQ(states[0].version(), version + 1);
  EXPECT_EQ(states[1].camera_health().status(), kapfix::v1::DEVICE_OK);
  EXPECT_TRUE(states[1].camera_health().reason().empty());
  EXPECT_EQ(states[1].version(), version + 2);
}

TEST(StateKeeperTest, SetSettingsPublishesTheNewState) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  AgentConfig settings;
  settings.gains.set_p(0.3F);
  keeper.SetSettings(settings);
  EXPECT_FLOAT_EQ(keeper.settings()->gains.p(), 0.3F);
  const auto states = sink.Messages<kapfix::v1::AgentState>();
  ASSERT_EQ(states.size(), 1u);
  EXPECT_FLOAT_EQ(states[0].gains().p(), 0.3F);
}

// Holds the first caller of Count() (a thread in the middle of publishing a state, between
// its snapshot and the sink) until Release(); later callers pass.
class HeldPhotoCount {
 public:
  std::uint64_t Count() {
    std::unique_lock lock(mutex_);
    if (calls_++ == 0) {
      entered_ = true;
      changed_.notify_all();
      changed_.wait(lock, [this] { return released_; });
    }
    return 0;
  }
  void WaitUntilHeld() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return entered_; });
  }
  void Release() {
    std::lock_guard lock(mutex_);
    released_ = true;
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int calls_ = 0;
  bool entered_ = false;
  bool released_ = false;
};

// The race of StationWithAgent.ChangesAGain: the control thread publishes a mode change and is
// held after taking its snapshot; meanwhile a command changes a gain. The last state sent
// must be the newest, and versions must never go down.
TEST(StateKeeperTest, ANewerStateIsNeverFollowedByAnOlderOne) {
  RecordingStreamSink sink;
  HeldPhotoCount photos;
  StateKeeper keeper(AgentConfig{}, sink, true, [&photos] { return photos.Count(); });
  std::thread control([&keeper] { keeper.OnModeChanged(AgentMode::kFixate, 0); });
  photos.WaitUntilHeld();
  AgentConfig settings;
  settings.gains.set_p(0.75F);
  keeper.SetSettings(settings);  // must not wait for the held thread
  photos.Release();
  control.join();

  const auto states = sink.Messages<kapfix::v1::AgentState>();
  ASSERT_FALSE(states.empty());
  EXPECT_FLOAT_EQ(states.back().gains().p(), 0.75F);
  EXPECT_EQ(states.back().mode(), kapfix::v1::MODE_FIXATE);
  EXPECT_EQ(states.back().version(), keeper.State().version());
  for (std::size_t i = 1; i < states.size(); ++i) {
    EXPECT_GT(states[i].version(), states[i - 1].version()) << "state " << i;
  }
}

TEST(StateKeeperTest, EveryChangeRaisesTheVersion) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  const std::uint64_t before = keeper.State().version();
  keeper.OnModeChanged(AgentMode::kSsp, 0);
  const std::uint64_t after_mode = keeper.State().version();
  keeper.SetSettings(AgentConfig{});
  EXPECT_GT(after_mode, before);
  EXPECT_GT(keeper.State().version(), after_mode);
}

TEST(StateKeeperTest, PublishingAgainWithoutAChangeKeepsTheVersion) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  keeper.PublishState();
  keeper.PublishState();
  const auto states = sink.Messages<kapfix::v1::AgentState>();
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].version(), states[1].version());
}

TEST(StateKeeperTest, ARefusedUpdateChangesAndPublishesNothing) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  const auto before = keeper.settings();
  std::string error;
  const auto updated = keeper.UpdateSettings(
      [](AgentConfig* config, std::string* why) {
        config->gains.set_p(99);
        *why = "kp too large";
        return false;
      },
      &error);
  EXPECT_EQ(updated, nullptr);
  EXPECT_EQ(error, "kp too large");
  EXPECT_EQ(keeper.settings(), before);
  EXPECT_EQ(sink.size(), 0u);
}

TEST(StateKeeperTest, ASnapshotStaysAsItWasAfterAChange) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  const auto snapshot = keeper.settings();
  const double kp = snapshot->gains.p();
  AgentConfig changed;
  changed.gains.set_p(static_cast<float>(kp / 2));
  keeper.SetSettings(changed);
  EXPECT_DOUBLE_EQ(snapshot->gains.p(), kp);
  EXPECT_DOUBLE_EQ(keeper.settings()->gains.p(), kp / 2);
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
  EXPECT_DOUBLE_EQ(keeper.settings()->active_lens().DegPerPxPan(), 0.05);
  EXPECT_DOUBLE_EQ(keeper.settings()->active_lens().DegPerPxTilt(), 0.07);
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
  EXPECT_TRUE(keeper.settings()->IsValid(&error)) << error;
  EXPECT_DOUBLE_EQ(keeper.settings()->active_lens().DegPerPxPan(), 0.15);
}

TEST(StateKeeperTest, UnusableCalibrationLeavesTheLensAsItWas) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile("default");
  report.set_finished(true);
  keeper.OnCalibrationReport(report, std::nullopt);
  EXPECT_DOUBLE_EQ(keeper.settings()->active_lens().DegPerPxPan(), 0.1);
}

}  // namespace
}  // namespace kapfix::agent
