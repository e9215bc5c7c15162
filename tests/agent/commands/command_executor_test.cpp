// CommandExecutor: settings commands reach the StateKeeper (or are refused with the field
// named), a photo is refused when the disk cannot take it, request_state answers with the
// state and the names of the photos it sends again.
#include "agent/commands/command_executor.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "tests/agent/support/recording_stream_sink.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::RecordingStreamSink;
using kapfix::testing::TempDir;

// The executor over real parts, all publishing into one recording sink.
struct Rig {
  explicit Rig(const std::filesystem::path& photo_dir) : store(photo_dir) {}

  AgentConfig config;
  RecordingStreamSink sink;
  StateKeeper state{config, sink, true, nullptr};
  ModeRunner modes{config, ModeRunnerOptions{}, state};
  PhotoStore store;
  PhotoTaker photos{store, sink, [] { return std::string("default"); }};
  VideoDownlink video{sink, config.video};
  std::vector<kapfix::v1::CameraSettings> camera;  // what reached the camera, in order
  CommandExecutor executor{CommandTargets{
      state, modes, photos, video,
      [this](const kapfix::v1::CameraSettings& settings) { camera.push_back(settings); }, true}};
};

kapfix::v1::Command Gains(float p) {
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_p(p);
  return command;
}

TEST(CommandExecutorTest, SetGainsUpdatesTheSettings) {
  TempDir temp;
  Rig rig(temp.path());
  const kapfix::v1::Reply reply = rig.executor.Execute(Gains(0.4F));
  EXPECT_TRUE(reply.ok()) << reply.reason();
  EXPECT_FLOAT_EQ(static_cast<float>(rig.state.settings()->gains.p()), 0.4F);
}

TEST(CommandExecutorTest, SetGainsPublishesTheNewState) {
  TempDir temp;
  Rig rig(temp.path());
  rig.executor.Execute(Gains(0.4F));
  const auto states = rig.sink.Messages<kapfix::v1::AgentState>();
  ASSERT_FALSE(states.empty());
  EXPECT_FLOAT_EQ(states.back().gains().p(), 0.4F);
}

TEST(CommandExecutorTest, OutOfRangeGainIsRefusedAndChangesNothing) {
  TempDir temp;
  Rig rig(temp.path());
  const kapfix::v1::Reply reply = rig.executor.Execute(Gains(25.0F));  // kp is (0, 10]
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
  EXPECT_NE(reply.reason().find("gains.p"), std::string::npos) << reply.reason();
  EXPECT_DOUBLE_EQ(rig.state.settings()->gains.p(), AgentConfig{}.gains.p());
}

// The camera gets the whole settings message held after the command, not only the change: a
// camera that was reopened meanwhile gets everything back.
TEST(CommandExecutorTest, SetCameraHandsTheCameraTheWholeSettingsMessage) {
  TempDir temp;
  Rig rig(temp.path());
  kapfix::v1::Command exposure;
  exposure.mutable_set_camera()->set_exposure_us(2000);
  ASSERT_TRUE(rig.executor.Execute(exposure).ok());
  kapfix::v1::Command gain;
  gain.mutable_set_camera()->set_gain_db(6);
  ASSERT_TRUE(rig.executor.Execute(gain).ok());
  ASSERT_EQ(rig.camera.size(), 2u);
  EXPECT_FLOAT_EQ(rig.camera.back().gain_db(), 6);
  EXPECT_FLOAT_EQ(rig.camera.back().exposure_us(), 2000);
  EXPECT_FALSE(rig.camera.back().has_auto_exposure()) << "a fixed exposure replaced it";
}

TEST(CommandExecutorTest, SetPhotoIntervalIsStoredInTheSettings) {
  TempDir temp;
  Rig rig(temp.path());
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_interval_s(5);
  EXPECT_TRUE(rig.executor.Execute(command).ok());
  EXPECT_FLOAT_EQ(rig.state.settings()->photo.interval_s(), 5.0F);
  EXPECT_EQ(rig.state.settings()->photo.shutter(), kapfix::v1::SHUTTER_INTERVAL)
      << "the fields the command leaves keep their values";
}

// Issue 13: set_photo was "command not known"; now it is applied, shown in the state, and the
// photo taker's shutter follows it.
TEST(CommandExecutorTest, SetPhotoIsAppliedShownAndReachesTheShutter) {
  TempDir temp;
  Rig rig(temp.path() / "photos");
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  command.mutable_set_photo()->set_exposure_ms(5.0F);
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  ASSERT_TRUE(reply.ok()) << reply.reason();
  EXPECT_EQ(rig.state.settings()->photo.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_EQ(rig.executor.State().photo().shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(rig.executor.State().photo().exposure_ms(), 5.0F);

  kapfix::v1::Command take;
  take.mutable_take_photo()->set_note("ridge");
  ASSERT_TRUE(rig.executor.Execute(take).ok());
  TelemetryRecord record;
  record.found = true;
  rig.photos.OnStep(CapturedFrame{cv::Mat(24, 32, CV_8UC3, cv::Scalar(90, 90, 90)), 0, 0},
                    FrameOutcome{}, record);
  rig.photos.Flush();
  const auto saved = rig.photos.Saved();
  ASSERT_EQ(saved.size(), 1u);
  EXPECT_EQ(saved[0].shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(saved[0].exposure_ms(), 5.0F);
  // A first frame: nothing to predict from yet.
  EXPECT_NE(saved[0].shutter_reason().find("no trained predictor"), std::string::npos)
      << saved[0].shutter_reason();
}

TEST(CommandExecutorTest, SetPhotoWindowBeyondTheCapIsRefused) {
  TempDir temp;
  Rig rig(temp.path());
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_window_s(12.0F);  // the cap is 10 s
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
  // The one check across the two fields is the shutter's own (BestPhaseShutterOptions).
  EXPECT_NE(reply.reason().find("longer than its cap"), std::string::npos) << reply.reason();
  EXPECT_FLOAT_EQ(rig.state.settings()->photo.window_s(), 0.0F);
}

TEST(CommandExecutorTest, TakePhotoIsAcceptedWhenTheFolderIsWritable) {
  TempDir temp;
  Rig rig(temp.path() / "photos");
  kapfix::v1::Command command;
  command.mutable_take_photo()->set_note("bridge");
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  EXPECT_TRUE(reply.ok()) << reply.reason();
}

TEST(CommandExecutorTest, TakePhotoIsRefusedAsStorageWhenTheFolderCannotBeWritten) {
  TempDir temp;
  const std::filesystem::path not_a_folder = temp.path() / "photos";
  std::ofstream(not_a_folder) << "a regular file";
  Rig rig(not_a_folder);
  kapfix::v1::Command command;
  command.mutable_take_photo();
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_STORAGE);
  EXPECT_NE(reply.reason().find(not_a_folder.string()), std::string::npos) << reply.reason();
}

TEST(CommandExecutorTest, RequestStateRepliesWithTheState) {
  TempDir temp;
  Rig rig(temp.path());
  rig.executor.Execute(Gains(0.6F));
  kapfix::v1::Command command;
  command.mutable_request_state();
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  ASSERT_TRUE(reply.ok()) << reply.reason();
  ASSERT_TRUE(reply.has_state());
  EXPECT_FLOAT_EQ(reply.state().gains().p(), 0.6F);
  EXPECT_EQ(reply.state().search().strategy(), rig.config.search.strategy);
  EXPECT_TRUE(reply.state().simulated());
}

TEST(CommandExecutorTest, RequestStateCanAskForTheSliceReportAgain) {
  TempDir temp;
  Rig rig(temp.path());
  kapfix::v1::SliceReport report;
  report.set_recommended_slice(2);
  report.set_finished(true);
  rig.state.OnSliceReport(report);
  kapfix::v1::Command command;
  command.mutable_request_state()->set_resend_slice_report(true);
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  ASSERT_TRUE(reply.ok()) << reply.reason();
  EXPECT_EQ(reply.state().last_slice_report().recommended_slice(), 2u);
  EXPECT_EQ(rig.sink.Messages<kapfix::v1::SliceReport>().size(), 2u);
}

TEST(CommandExecutorTest, RequestStateNamesTheStoredPhotosItResends) {
  TempDir temp;
  Rig rig(temp.path());
  const cv::Mat image(16, 16, CV_8UC3, cv::Scalar(10, 20, 30));
  std::vector<std::string> names;
  for (const std::int64_t time_us : {1000, 2000, 3000}) {
    kapfix::v1::PhotoMetadata metadata;
    metadata.set_capture_time_us(time_us);
    names.push_back(rig.store.Save(image, metadata, nullptr).file_name());
  }
  kapfix::v1::Command command;
  command.mutable_request_state()->set_resend_photos_since_us(2000);
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  ASSERT_TRUE(reply.ok()) << reply.reason();
  ASSERT_EQ(reply.photos_resent_size(), 2);
  EXPECT_EQ(reply.photos_resent(0), names[1]);
  EXPECT_EQ(reply.photos_resent(1), names[2]);
}

TEST(CommandExecutorTest, UnknownModeIsRefusedAsOutOfRange) {
  TempDir temp;
  Rig rig(temp.path());
  kapfix::v1::Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_UNSPECIFIED);
  const kapfix::v1::Reply reply = rig.executor.Execute(command);
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
}

TEST(CommandExecutorTest, EmptyCommandIsRefusedAsUnknown) {
  TempDir temp;
  Rig rig(temp.path());
  const kapfix::v1::Reply reply = rig.executor.Execute(kapfix::v1::Command());
  EXPECT_FALSE(reply.ok());
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND);
}

}  // namespace
}  // namespace kapfix::agent
