#include "agent/resume/resume_recorder.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "tests/support/temp_dir.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

// The state keeper's place: counts what reaches it.
class CountingModeEvents : public ModeEvents {
 public:
  std::vector<std::pair<AgentMode, int>> modes;
  int slice_reports = 0;
  std::vector<bool> resumes;
  void OnModeChanged(AgentMode mode, int slice) override { modes.emplace_back(mode, slice); }
  void OnSliceReport(const kapfix::v1::SliceReport& /*report*/) override { ++slice_reports; }
  void OnPssReport(const kapfix::v1::PssReport& /*report*/) override {}
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& /*report*/,
                           const std::optional<LensCalibration>& /*applied*/) override {}
  void OnFreeSwingRecorded(const std::string& /*path*/, const std::string& /*error*/) override {}
  void OnResumeEnded(bool resumed) override { resumes.push_back(resumed); }
};

ResumeRecord Stored(const TempDir& dir) {
  std::string error;
  std::optional<ResumeRecord> record = ResumeStore(dir.path()).Load(&error);
  EXPECT_TRUE(record.has_value()) << error;
  return record.value_or(ResumeRecord{});
}

kapfix::v1::Command Gains(std::optional<float> p, std::optional<float> i) {
  kapfix::v1::Command command;
  if (p) command.mutable_set_gains()->set_p(*p);
  if (i) command.mutable_set_gains()->set_i(*i);
  return command;
}

TEST(ResumeRecorderTest, PartialSettingsCommandsAddUp) {
  TempDir dir;
  ResumeStore store(dir.path());
  CountingModeEvents next;
  ResumeRecorder recorder(store, next, {}, "default");
  recorder.OnSettingsApplied(Gains(0.6F, std::nullopt));
  recorder.OnSettingsApplied(Gains(std::nullopt, 0.2F));
  recorder.OnSettingsApplied(Gains(0.7F, std::nullopt));
  recorder.Flush();
  const ResumeRecord record = Stored(dir);
  ASSERT_EQ(record.settings.size(), 1u);
  EXPECT_FLOAT_EQ(record.settings[0].set_gains().p(), 0.7F);
  EXPECT_FLOAT_EQ(record.settings[0].set_gains().i(), 0.2F);
  EXPECT_FALSE(record.settings[0].set_gains().has_d());
}

TEST(ResumeRecorderTest, TheLaterOfFixedAndAutomaticExposureCounts) {
  TempDir dir;
  ResumeStore store(dir.path());
  CountingModeEvents next;
  ResumeRecorder recorder(store, next, {}, "default");
  kapfix::v1::Command automatic;
  automatic.mutable_set_camera()->set_auto_exposure(true);
  kapfix::v1::Command fixed;
  fixed.mutable_set_camera()->set_exposure_us(2000);
  recorder.OnSettingsApplied(automatic);
  recorder.OnSettingsApplied(fixed);
  recorder.Flush();
  ResumeRecord record = Stored(dir);
  ASSERT_EQ(record.settings.size(), 1u);
  EXPECT_FALSE(record.settings[0].set_camera().has_auto_exposure());
  EXPECT_FLOAT_EQ(record.settings[0].set_camera().exposure_us(), 2000);
  recorder.OnSettingsApplied(automatic);
  recorder.Flush();
  record = Stored(dir);
  EXPECT_FALSE(record.settings[0].set_camera().has_exposure_us());
  EXPECT_TRUE(record.settings[0].set_camera().auto_exposure());
}

TEST(ResumeRecorderTest, ALensSwitchIsStoredAfterTheProfilesOptics) {
  TempDir dir;
  ResumeStore store(dir.path());
  CountingModeEvents next;
  ResumeRecorder recorder(store, next, {}, "default");
  kapfix::v1::Command optics;  // no name: the profile in use
  optics.mutable_set_lens()->set_focal_length_mm(8);
  optics.mutable_set_lens()->set_pixel_pitch_um(3);
  kapfix::v1::Command wide;
  wide.mutable_set_lens()->set_name("wide");
  recorder.OnSettingsApplied(optics);
  recorder.OnSettingsApplied(wide);
  recorder.Flush();
  const ResumeRecord record = Stored(dir);
  ASSERT_EQ(record.settings.size(), 2u);
  EXPECT_EQ(record.settings[0].set_lens().name(), "default");
  EXPECT_FLOAT_EQ(record.settings[0].set_lens().focal_length_mm(), 8);
  EXPECT_EQ(record.settings[1].set_lens().name(), "wide");
  EXPECT_FALSE(record.settings[1].set_lens().has_focal_length_mm());
}

TEST(ResumeRecorderTest, ModeSliceAndReferenceAreStoredAndEveryEventGoesOn) {
  TempDir dir;
  ResumeStore store(dir.path());
  CountingModeEvents next;
  ResumeRecorder recorder(store, next, {}, "default");
  const cv::Mat frame = kapfix::testing::LoadOpenCvPhoto("aero1.jpg");
  recorder.OnReferenceTaken(frame, {4.0, -2.0});
  recorder.OnModeChanged(AgentMode::kFixate, 4);
  recorder.OnSliceReport(kapfix::v1::SliceReport{});
  recorder.OnResumeEnded(true);
  recorder.Flush();
  const ResumeRecord record = Stored(dir);
  EXPECT_EQ(record.mode, AgentMode::kFixate);
  EXPECT_EQ(record.slice, 4);
  EXPECT_DOUBLE_EQ(record.reference_at.pan_deg, 4.0);
  EXPECT_EQ(cv::norm(record.reference_frame, frame, cv::NORM_INF), 0.0);
  EXPECT_EQ(next.modes, (std::vector<std::pair<AgentMode, int>>{{AgentMode::kFixate, 4}}));
  EXPECT_EQ(next.slice_reports, 1);
  EXPECT_EQ(next.resumes, std::vector<bool>{true});
}

TEST(ResumeRecorderTest, WhatARunResumedFromIsKeptWhenOnlyASettingChanges) {
  TempDir dir;
  ResumeStore store(dir.path());
  ResumeRecord start;
  start.settings.push_back(Gains(0.6F, std::nullopt));
  start.mode = AgentMode::kFixate;
  start.slice = 2;
  start.reference_frame = kapfix::testing::LoadOpenCvPhoto("aero3.jpg");
  CountingModeEvents next;
  ResumeRecorder recorder(store, next, start, "default");
  kapfix::v1::Command interval;
  interval.mutable_set_photo()->set_interval_s(3.0F);
  recorder.OnSettingsApplied(interval);
  recorder.Flush();
  const ResumeRecord record = Stored(dir);
  ASSERT_EQ(record.settings.size(), 2u);
  EXPECT_FLOAT_EQ(record.settings[0].set_gains().p(), 0.6F);
  EXPECT_FLOAT_EQ(record.settings[1].set_photo().interval_s(), 3.0F);
  EXPECT_EQ(record.mode, AgentMode::kFixate);
  EXPECT_EQ(record.slice, 2);
  EXPECT_EQ(cv::norm(record.reference_frame, start.reference_frame, cv::NORM_INF), 0.0);
}

TEST(ResumeRecorderTest, NothingIsWrittenWhenNothingChanges) {
  TempDir dir;
  ResumeStore store(dir.path());
  CountingModeEvents next;
  ResumeRecorder recorder(store, next, {}, "default");
  recorder.OnModeChanged(AgentMode::kFixate, 3);
  recorder.Flush();
  EXPECT_EQ(recorder.writes(), 1u);
  for (int i = 0; i < 10; ++i) recorder.OnModeChanged(AgentMode::kFixate, 3);  // the same again
  recorder.OnSliceReport(kapfix::v1::SliceReport{});
  recorder.Flush();
  EXPECT_EQ(recorder.writes(), 1u);
}

}  // namespace
}  // namespace kapfix::agent
