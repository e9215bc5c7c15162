// ModeRunner on the frames of a synthetic free swing: fixate takes its reference from the
// first frame; SSP and PSS finish at their deadline with a report and fall back to idle; the
// slice and the settings change between frames; a free swing is recorded as CSV.
#include "agent/modes/mode_runner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "common/selection/slice_geometry.hpp"
#include "tests/common/selection/swing_frames.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

const cv::Size kFrame(200, 140);  // small: PSS can try 50 and 100 px but not 150
constexpr int kSlices = 5;
constexpr int kPatch = 40;
constexpr std::int64_t kFramePeriodUs = 33'333;

// Copies what the runner reports; called on the test's (control) thread only.
class RecordingModeEvents : public ModeEvents {
 public:
  std::vector<std::pair<AgentMode, int>> modes;
  std::vector<kapfix::v1::SliceReport> slice_reports;
  std::vector<kapfix::v1::PssReport> pss_reports;
  std::vector<std::pair<std::string, std::string>> recordings;  // path, error

  void OnModeChanged(AgentMode mode, int slice) override { modes.emplace_back(mode, slice); }
  void OnSliceReport(const kapfix::v1::SliceReport& report) override {
    slice_reports.push_back(report);
  }
  void OnPssReport(const kapfix::v1::PssReport& report) override { pss_reports.push_back(report); }
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& /*report*/,
                           const std::optional<LensCalibration>& /*applied*/) override {}
  void OnFreeSwingRecorded(const std::string& path, const std::string& error) override {
    recordings.emplace_back(path, error);
  }

  int finished_slice_reports() const {
    return static_cast<int>(std::count_if(slice_reports.begin(), slice_reports.end(),
                                          [](const auto& r) { return r.finished(); }));
  }
};

AgentConfig SmallConfig() {
  AgentConfig config;
  config.search.strategy = "all";
  config.search.sampling.kind = SamplingKind::kAll;
  config.search.patch_px = kPatch;
  config.search.slices = kSlices;
  config.search.range_px = 24;
  return config;
}

ModeRunnerOptions Options(AgentMode start, const std::string& recordings_dir = "") {
  ModeRunnerOptions options;
  options.start_mode = start;
  options.recordings_dir = recordings_dir;
  return options;
}

// [px] window positions of the swing the frames are cut from.
std::vector<int> Positions(int frames) { return kapfix::testing::PendulumPositions(frames, 8, 12); }

// BGR frames of a free swing along x, numbered from `first_index`.
std::vector<CapturedFrame> Swing(int frames, std::uint64_t first_index = 0) {
  cv::Mat scene;
  cv::cvtColor(kapfix::testing::SmoothTexture({320, 220}, 5), scene, cv::COLOR_GRAY2BGR);
  const std::vector<cv::Mat> images =
      kapfix::testing::SwingFrames(scene, kFrame, Positions(frames));
  std::vector<CapturedFrame> captured;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::uint64_t index = first_index + i;
    captured.push_back(
        CapturedFrame{images[i], static_cast<std::int64_t>(index) * kFramePeriodUs, index});
  }
  return captured;
}

FrameOutcome Feed(ModeRunner& runner, const CapturedFrame& frame) {
  return runner.Process(frame, ServoTargets{}, kFramePeriodUs * 1e-6);
}

TEST(ModeRunnerTest, StartModeFixateTakesTheFirstFrameAsReference) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(1, 7);
  const FrameOutcome outcome = Feed(runner, frames[0]);
  EXPECT_EQ(outcome.mode, AgentMode::kFixate);
  ASSERT_TRUE(outcome.reference_frame.has_value());
  EXPECT_EQ(*outcome.reference_frame, 7u);
  EXPECT_EQ(outcome.patch, SlicePatch(kFrame, kSlices, (kSlices + 1) / 2, kPatch));
  EXPECT_EQ(runner.mode(), AgentMode::kFixate);
}

TEST(ModeRunnerTest, FixateMeasuresEachFrameAgainstTheFirst) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(6, 7);
  const std::vector<int> positions = Positions(6);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const FrameOutcome outcome = Feed(runner, frames[i]);
    ASSERT_TRUE(outcome.step.match.found) << i;
    EXPECT_EQ(*outcome.reference_frame, 7u);
    // The window moved right by p_i − p_0: the content, by as much to the left.
    EXPECT_NEAR(outcome.step.match.displacement.x, -(positions[i] - positions[0]), 0.5) << i;
  }
}

TEST(ModeRunnerTest, SspFinishesAtTheDeadlineAndReportsTheSlice) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
  runner.RequestMode(AgentMode::kSsp, SwingDeadline{10, 100.0});
  const std::vector<CapturedFrame> frames = Swing(10);
  for (std::size_t i = 0; i + 1 < frames.size(); ++i) {
    EXPECT_EQ(Feed(runner, frames[i]).mode, AgentMode::kSsp);
  }
  EXPECT_EQ(events.finished_slice_reports(), 0);  // not before the deadline
  Feed(runner, frames.back());
  ASSERT_EQ(events.finished_slice_reports(), 1);
  const kapfix::v1::SliceReport& report = events.slice_reports.back();
  EXPECT_TRUE(report.finished());
  EXPECT_EQ(report.slices_size(), kSlices);
  EXPECT_GE(report.recommended_slice(), 1u);
  EXPECT_LE(report.recommended_slice(), static_cast<std::uint32_t>(kSlices));
}

TEST(ModeRunnerTest, FinishedSspFallsBackToIdleOnTheRecommendedSlice) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
  runner.RequestMode(AgentMode::kSsp, SwingDeadline{10, 100.0});
  for (const CapturedFrame& frame : Swing(10)) Feed(runner, frame);
  ASSERT_FALSE(events.slice_reports.empty());
  const auto recommended = static_cast<int>(events.slice_reports.back().recommended_slice());
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);
  EXPECT_EQ(runner.slice(), recommended);
  ASSERT_FALSE(events.modes.empty());
  EXPECT_EQ(events.modes.back(), std::make_pair(AgentMode::kIdle, recommended));
}

TEST(ModeRunnerTest, RequestSliceTakesEffectOnTheNextFrame) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(2);
  Feed(runner, frames[0]);
  runner.RequestSlice(2);
  EXPECT_EQ(runner.slice(), 3);  // not before the next frame
  const FrameOutcome outcome = Feed(runner, frames[1]);
  EXPECT_EQ(runner.slice(), 2);
  EXPECT_EQ(outcome.slice, 2);
  EXPECT_EQ(outcome.patch, SlicePatch(kFrame, kSlices, 2, kPatch));
  EXPECT_EQ(outcome.mode, AgentMode::kFixate);
}

TEST(ModeRunnerTest, RequestedSliceBeyondTheCountIsClamped) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
  runner.RequestSlice(99);
  Feed(runner, Swing(1)[0]);
  EXPECT_EQ(runner.slice(), kSlices);
}

TEST(ModeRunnerTest, PssFinishesWithCandidatesThatFitTheFrame) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
  runner.RequestMode(AgentMode::kPss, SwingDeadline{8, 100.0});
  for (const CapturedFrame& frame : Swing(8)) Feed(runner, frame);
  ASSERT_FALSE(events.pss_reports.empty());
  const kapfix::v1::PssReport& report = events.pss_reports.back();
  ASSERT_TRUE(report.finished());
  ASSERT_EQ(report.candidates_size(), 2);  // 50 and 100 px; 150 px is taller than the frame
  std::vector<std::uint32_t> sizes;
  for (const auto& candidate : report.candidates()) {
    EXPECT_LE(candidate.patch_size_px(), static_cast<std::uint32_t>(kFrame.height));
    sizes.push_back(candidate.patch_size_px());
  }
  EXPECT_NE(std::find(sizes.begin(), sizes.end(), report.recommended_patch_size_px()), sizes.end());
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);
}

TEST(ModeRunnerTest, FreeSwingRecordingWritesOneCsvRowPerFrameAfterTheFirst) {
  TempDir temp;
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle, temp.path().string()), events);
  runner.RequestMode(AgentMode::kRecordFreeSwing, SwingDeadline{8, 100.0});
  for (const CapturedFrame& frame : Swing(8)) Feed(runner, frame);
  ASSERT_EQ(events.recordings.size(), 1u);
  EXPECT_EQ(events.recordings[0].second, "");
  const std::filesystem::path path = events.recordings[0].first;
  EXPECT_EQ(path.parent_path(), temp.path());
  EXPECT_EQ(path.extension(), ".csv");
  std::ifstream csv(path);
  std::vector<std::string> rows;
  for (std::string line; std::getline(csv, line);) {
    if (!line.empty() && line[0] != '#' && line != "capture_time_us,displacement_px") {
      rows.push_back(line);
    }
  }
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[0].substr(0, rows[0].find(',')), std::to_string(kFramePeriodUs));  // frame 1
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);
}

TEST(ModeRunnerTest, FreeSwingWithoutARecordingsFolderFallsBackToIdle) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
  runner.RequestMode(AgentMode::kRecordFreeSwing, SwingDeadline{8, 100.0});
  const FrameOutcome outcome = Feed(runner, Swing(1)[0]);
  EXPECT_EQ(outcome.mode, AgentMode::kIdle);
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);
}

TEST(ModeRunnerTest, SettingsWithAnotherStrategyApplyBetweenFramesAndKeepFixating) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(3);
  Feed(runner, frames[0]);
  const int exhaustive = Feed(runner, frames[1]).step.match.evaluations;
  AgentConfig settings = SmallConfig();
  settings.search.strategy = "h23";
  runner.RequestSettings(settings);
  const FrameOutcome outcome = Feed(runner, frames[2]);
  EXPECT_EQ(outcome.mode, AgentMode::kFixate);
  ASSERT_TRUE(outcome.reference_frame.has_value());
  EXPECT_EQ(*outcome.reference_frame, 0u);  // the view fixated stays the one to hold
  EXPECT_TRUE(outcome.step.match.found);
  EXPECT_LT(outcome.step.match.evaluations, exhaustive);  // the hierarchical search is in use
}

// Issue 15, item 7: a settings command that changes nothing rebuilt the controller, and its
// state (integral, prediction history) was lost: 4–8 px of error for ~50 frames. Two runners
// on the same frames, one told the same settings again midway, must command the same angles.
TEST(ModeRunnerTest, SettingsThatChangeNothingKeepTheControllersState) {
  AgentConfig config = SmallConfig();
  config.controller.kind = ControllerKind::kPid;
  config.controller.ki = 0.2;  // an integral term: state a rebuild would lose
  RecordingModeEvents events_a;
  RecordingModeEvents events_b;
  ModeRunner untouched(config, Options(AgentMode::kFixate), events_a);
  ModeRunner told_again(config, Options(AgentMode::kFixate), events_b);
  const std::vector<CapturedFrame> frames = Swing(12);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == 6) told_again.RequestSettings(config);
    const FrameOutcome a = Feed(untouched, frames[i]);
    const FrameOutcome b = Feed(told_again, frames[i]);
    EXPECT_EQ(a.step.targets.pan_deg, b.step.targets.pan_deg) << "frame " << i;
    EXPECT_EQ(a.step.targets.tilt_deg, b.step.targets.tilt_deg) << "frame " << i;
  }
}

// Issue 15, item 7: new gains reach the controller without a rebuild (bumpless). A rate
// limit raised where it never binds is a gain change that moves no target: the
// runner told it midway must command exactly what the untouched one does, integral and all.
TEST(ModeRunnerTest, AGainChangeKeepsTheControllersState) {
  AgentConfig config = SmallConfig();
  config.controller.kind = ControllerKind::kPid;
  config.controller.ki = 0.2;
  RecordingModeEvents events_a;
  RecordingModeEvents events_b;
  ModeRunner untouched(config, Options(AgentMode::kFixate), events_a);
  ModeRunner changed(config, Options(AgentMode::kFixate), events_b);
  AgentConfig faster = config;
  faster.controller.max_rate_deg_per_s = config.controller.max_rate_deg_per_s + 1;
  const std::vector<CapturedFrame> frames = Swing(12);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i == 6) changed.RequestSettings(faster);
    const FrameOutcome a = Feed(untouched, frames[i]);
    const FrameOutcome b = Feed(changed, frames[i]);
    EXPECT_DOUBLE_EQ(a.step.targets.pan_deg, b.step.targets.pan_deg) << "frame " << i;
  }
}

TEST(ModeRunnerTest, IdleHoldsTheServosWhereTheyAre) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
  const FrameOutcome outcome = runner.Process(Swing(1)[0], ServoTargets{3.0, -1.0}, 0.033);
  EXPECT_EQ(outcome.mode, AgentMode::kIdle);
  EXPECT_DOUBLE_EQ(outcome.step.targets.pan_deg, 3.0);
  EXPECT_DOUBLE_EQ(outcome.step.targets.tilt_deg, -1.0);
  EXPECT_FALSE(outcome.reference_frame.has_value());
}

}  // namespace
}  // namespace kapfix::agent
