// ModeRunner on the frames of a synthetic free swing: fixate takes its reference from the
// first frame; SSP and PSS finish at their deadline with a report and fall back to idle; the
// slice and the settings change between frames; a free swing is recorded as CSV; a held lock
// that trails the view and one riding out untrusted frames are logged apart.
#include "agent/modes/mode_runner.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <sstream>
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
  std::vector<bool> resumes;  // OnResumeEnded's
  int references_taken = 0;
  void OnResumeEnded(bool resumed) override { resumes.push_back(resumed); }
  void OnReferenceTaken(const cv::Mat& /*frame_bgr*/, const ServoTargets& /*servos*/) override {
    ++references_taken;
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

// BGR frames cut at these window positions [px] along x, numbered from `first_index`.
std::vector<CapturedFrame> FramesAt(const std::vector<int>& positions,
                                    std::uint64_t first_index = 0) {
  cv::Mat scene;
  cv::cvtColor(kapfix::testing::SmoothTexture({320, 220}, 5), scene, cv::COLOR_GRAY2BGR);
  const std::vector<cv::Mat> images = kapfix::testing::SwingFrames(scene, kFrame, positions);
  std::vector<CapturedFrame> captured;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const std::uint64_t index = first_index + i;
    captured.push_back(
        CapturedFrame{images[i], static_cast<std::int64_t>(index) * kFramePeriodUs, index});
  }
  return captured;
}

// BGR frames of a free swing along x, numbered from `first_index`.
std::vector<CapturedFrame> Swing(int frames, std::uint64_t first_index = 0) {
  return FramesAt(Positions(frames), first_index);
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

// What the agent logs while `run` runs (spdlog's default logger, restored after).
std::string LoggedDuring(const std::function<void()>& run) {
  std::ostringstream log;
  const std::shared_ptr<spdlog::logger> previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>(
      "test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  run();
  spdlog::set_default_logger(previous);
  return log.str();
}

// Paints the band of `slice`'s patch in `image`, as far as the search reaches, one flat grey:
// that patch then matches itself equally well at every shift.
void PaintSliceBandFlat(cv::Mat& image, int slice) {
  const cv::Rect patch = SlicePatch(kFrame, kSlices, slice, kPatch);
  const int top = std::max(0, patch.y - 24 - 4);
  const int bottom = std::min(kFrame.height, patch.br().y + 24 + 4);
  image(cv::Rect(0, top, kFrame.width, bottom - top)).setTo(cv::Scalar(90, 90, 90));
}

// The first frame of Swing with the middle slice's band (the default slice) flat; the other
// slices are textured.
CapturedFrame FrameWithAFlatMiddle() {
  CapturedFrame frame = Swing(1)[0];
  PaintSliceBandFlat(frame.image, (kSlices + 1) / 2);
  return frame;
}

TEST(ModeRunnerTest, AWeakPatchOnTheAgentsSliceGivesWayToTheNearestSurePatch) {
  RecordingModeEvents events;
  FrameOutcome outcome;
  const std::string log = LoggedDuring([&] {
    ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
    outcome = Feed(runner, FrameWithAFlatMiddle());
  });
  const int middle = (kSlices + 1) / 2;
  EXPECT_NE(outcome.slice, middle) << log;
  EXPECT_EQ(outcome.mode, AgentMode::kFixate);
  EXPECT_EQ(outcome.patch, SlicePatch(kFrame, kSlices, outcome.slice, kPatch));
  EXPECT_NE(log.find("slice 3's patch is weak here"), std::string::npos) << log;
  EXPECT_NE(log.find("the same view is held by slice " + std::to_string(outcome.slice)),
            std::string::npos)
      << log;
  ASSERT_FALSE(events.modes.empty());
  EXPECT_EQ(events.modes.back(), std::make_pair(AgentMode::kFixate, outcome.slice))
      << "the operator sees the slice in use";
}

TEST(ModeRunnerTest, TheOperatorsPickedSliceIsKeptThoughItsPatchIsWeakAndTheNearestSureOneNamed) {
  RecordingModeEvents events;
  FrameOutcome outcome;
  const std::string log = LoggedDuring([&] {
    ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
    Feed(runner, Swing(1)[0]);
    runner.RequestSlice(3);
    outcome = Feed(runner, FrameWithAFlatMiddle());
  });
  EXPECT_EQ(outcome.slice, 3) << log;
  EXPECT_EQ(outcome.mode, AgentMode::kFixate);
  EXPECT_NE(log.find("slice 3's patch is weak here"), std::string::npos) << log;
  EXPECT_NE(log.find("select it (select_slice)"), std::string::npos) << log;
}

// After SSP, the frame fixated has SSP's slice's band painted flat; the operator fixates
// (`pick`: by confirming the recommendation with select_slice, else by a plain fixate). The
// outcome of that frame, the recommended slice and the log.
struct FixatedAfterSsp {
  FrameOutcome outcome;
  int recommended = 0;
  std::string log;
};

FixatedAfterSsp FixateAfterSspOnAFlatRecommendation(bool confirm) {
  RecordingModeEvents events;
  FixatedAfterSsp result;
  result.log = LoggedDuring([&] {
    ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
    runner.RequestMode(AgentMode::kSsp, SwingDeadline{10, 100.0});
    for (const CapturedFrame& frame : Swing(10)) Feed(runner, frame);
    ASSERT_EQ(events.finished_slice_reports(), 1);
    result.recommended = static_cast<int>(events.slice_reports.back().recommended_slice());
    CapturedFrame frame = Swing(1)[0];
    PaintSliceBandFlat(frame.image, result.recommended);
    frame.index = 20;
    if (confirm) {
      runner.RequestSlice(result.recommended);
    } else {
      runner.RequestMode(AgentMode::kFixate);
    }
    result.outcome = Feed(runner, frame);
  });
  return result;
}

// The fixation moved off SSP's flat recommendation along SSP's ranking, and said so.
void ExpectMovedAlongSspsRanking(const FixatedAfterSsp& fixated) {
  EXPECT_EQ(fixated.outcome.mode, AgentMode::kFixate);
  EXPECT_NE(fixated.outcome.slice, fixated.recommended) << fixated.log;
  EXPECT_NE(fixated.log.find("the next in SSP's ranking found surely"), std::string::npos)
      << fixated.log;
}

TEST(ModeRunnerTest, ConfirmingSspsRecommendationLetsAWeakPatchGiveWayAlongSspsRanking) {
  ExpectMovedAlongSspsRanking(FixateAfterSspOnAFlatRecommendation(/*confirm=*/true));
}

TEST(ModeRunnerTest, AfterSspAWeakPatchOfItsRecommendationGivesWayAlongSspsRanking) {
  ExpectMovedAlongSspsRanking(FixateAfterSspOnAFlatRecommendation(/*confirm=*/false));
}

// What the agent logs when the operator fixates on frame 8 of a running camera whose frame
// `before` (index) showed the view at window position `before_x` [px] and frame 8 at 40.
std::string LoggedFixatingAfter(std::uint64_t before, int before_x) {
  const std::vector<CapturedFrame> frames = FramesAt({before_x, 40});
  RecordingModeEvents events;
  return LoggedDuring([&] {
    ModeRunner runner(SmallConfig(), Options(AgentMode::kIdle), events);
    Feed(runner, CapturedFrame{frames[0].image, 0, before});
    runner.RequestMode(AgentMode::kFixate);
    Feed(runner, CapturedFrame{frames[1].image, 0, 8});
  });
}

constexpr const char* kSmearedLine = "px in the frame before the reference";

TEST(ModeRunnerTest, AReferenceTakenWhileTheViewMovesFastIsWarnedOfAsSmeared) {
  const std::string log = LoggedFixatingAfter(7, 28);  // 12 px in a frame
  EXPECT_NE(log.find("the view moved 12 px in the frame before the reference"), std::string::npos)
      << log;
}

TEST(ModeRunnerTest, AReferenceTakenWhileTheViewIsSlowIsNotWarnedOf) {
  const std::string log = LoggedFixatingAfter(7, 37);  // 3 px in a frame
  EXPECT_EQ(log.find(kSmearedLine), std::string::npos) << log;
}

// A frame that is not the one just before (frames lost between) says nothing of the speed.
TEST(ModeRunnerTest, AnEarlierFrameIsNotTakenForTheOneBeforeTheReference) {
  const std::string log = LoggedFixatingAfter(5, 28);
  EXPECT_EQ(log.find(kSmearedLine), std::string::npos) << log;
}

TEST(ModeRunnerTest, FixatingATexturedPatchWarnsOfNothing) {
  RecordingModeEvents events;
  const std::string log = LoggedDuring([&] {
    ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
    Feed(runner, Swing(1)[0]);
  });
  EXPECT_EQ(log.find("is weak"), std::string::npos) << log;
}

// Fixating frames at `positions` (servos still), with the frame at `flat_index` painted flat
// (a match nothing can trust); what the agent logs.
std::string LoggedWhileFixating(const std::vector<int>& positions, int flat_index = -1) {
  std::vector<CapturedFrame> frames = FramesAt(positions);
  if (flat_index >= 0) frames[flat_index].image.setTo(cv::Scalar(90, 90, 90));
  RecordingModeEvents events;
  return LoggedDuring([&] {
    ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
    for (const CapturedFrame& frame : frames) Feed(runner, frame);
  });
}

constexpr const char* kTrailsLine = "the loop trails it (lock held)";
constexpr const char* kRidesOutLine = "not claimed: the lock rides out untrusted frames";

TEST(ModeRunnerTest, AHeldLockThatTrailsTheViewIsLoggedAsTrailing) {
  // Four frames on the reference confirm the lock; then the view stands 16 px off (beyond
  // FixationLoopOptions::off_target_px) on a match that is trusted.
  const std::string log = LoggedWhileFixating({40, 40, 40, 40, 56});
  EXPECT_NE(log.find(kTrailsLine), std::string::npos) << log;
  EXPECT_EQ(log.find(kRidesOutLine), std::string::npos) << log;
}

TEST(ModeRunnerTest, ALockRidingOutAnUntrustedFrameIsLoggedAsNotClaimed) {
  // The same, with an untrusted frame before the off frame: the lock rides it out and steers
  // by the trusted frame after it, but must not call that frame a held view.
  const std::string log = LoggedWhileFixating({40, 40, 40, 40, 40, 56}, 4);
  EXPECT_NE(log.find(kRidesOutLine), std::string::npos) << log;
  EXPECT_EQ(log.find(kTrailsLine), std::string::npos) << log;
}

TEST(ModeRunnerTest, AViewOnTargetIsNotLoggedAsTrailing) {
  const std::string log = LoggedWhileFixating({40, 40, 40, 40, 42});
  EXPECT_EQ(log.find(kTrailsLine), std::string::npos) << log;
  EXPECT_EQ(log.find(kRidesOutLine), std::string::npos) << log;
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

// A free swing whose middle slice's band (the default slice, as far as the search reaches) is
// flat in every frame: a fixation there is lost at once and never re-acquired.
std::vector<CapturedFrame> SwingWithAFlatMiddle(int frames) {
  std::vector<CapturedFrame> swing = Swing(frames);
  for (CapturedFrame& frame : swing) PaintSliceBandFlat(frame.image, (kSlices + 1) / 2);
  return swing;
}

// The operator fixating the flat middle (select_slice, so that the agent keeps that slice) from
// the second frame, SSP after a lost lock 0.1 s (3 frames) and SSP's deadline 20 frames: the
// outcomes of the 59 frames fixated.
std::vector<FrameOutcome> FixateTheFlatMiddle(double ssp_after_lost_s,
                                              RecordingModeEvents* events) {
  AgentConfig config = SmallConfig();
  config.search.ssp_after_lost_s = ssp_after_lost_s;
  config.search.swing_frames = 20;
  ModeRunner runner(config, Options(AgentMode::kIdle), *events);
  const std::vector<CapturedFrame> swing = SwingWithAFlatMiddle(60);
  Feed(runner, swing.front());
  runner.RequestSlice((kSlices + 1) / 2);
  std::vector<FrameOutcome> outcomes;
  for (std::size_t i = 1; i < swing.size(); ++i) outcomes.push_back(Feed(runner, swing[i]));
  return outcomes;
}

TEST(ModeRunnerTest, ALockThatStaysLostMovesTheSameViewToTheSliceSspFindsAfterIt) {
  RecordingModeEvents events;
  std::string log;
  std::vector<FrameOutcome> outcomes;
  log = LoggedDuring([&] { outcomes = FixateTheFlatMiddle(0.1, &events); });
  const int middle = (kSlices + 1) / 2;
  ASSERT_FALSE(outcomes.empty());
  EXPECT_TRUE(outcomes[10].step.lock_lost) << "the flat patch must be lost first";
  EXPECT_EQ(outcomes[10].slice, middle);
  const FrameOutcome& last = outcomes.back();
  EXPECT_NE(last.slice, middle) << log;
  EXPECT_EQ(last.mode, AgentMode::kFixate);
  EXPECT_EQ(last.reference_frame, outcomes.front().reference_frame) << "the same view is held";
  EXPECT_FALSE(last.step.lock_lost) << log;
  EXPECT_TRUE(last.step.match.found);
  EXPECT_EQ(events.finished_slice_reports(), 1) << "the operator sees SSP's result";
  ASSERT_FALSE(events.modes.empty());
  EXPECT_EQ(events.modes.back(), std::make_pair(AgentMode::kFixate, last.slice));
  EXPECT_NE(log.find("SSP over the 20 frames of the lost lock recommends slice"), std::string::npos)
      << log;
}

TEST(ModeRunnerTest, WithSspAfterALostLockOffTheLostSliceStays) {
  RecordingModeEvents events;
  const std::vector<FrameOutcome> outcomes = FixateTheFlatMiddle(0, &events);
  EXPECT_EQ(outcomes.back().slice, (kSlices + 1) / 2);
  EXPECT_TRUE(outcomes.back().step.lock_lost);
  EXPECT_EQ(events.finished_slice_reports(), 0);
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
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);  // at once: the file is the worker's to write
  runner.FlushWork();
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
  config.gains.set_controller(kapfix::v1::CONTROLLER_KIND_PID);
  config.gains.set_i(0.2F);  // an integral term: state a rebuild would lose
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
  config.gains.set_controller(kapfix::v1::CONTROLLER_KIND_PID);
  config.gains.set_i(0.2F);
  RecordingModeEvents events_a;
  RecordingModeEvents events_b;
  ModeRunner untouched(config, Options(AgentMode::kFixate), events_a);
  ModeRunner changed(config, Options(AgentMode::kFixate), events_b);
  AgentConfig faster = config;
  faster.gains.set_rate_limit_deg_per_s(config.gains.rate_limit_deg_per_s() + 1.0F);
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

// Issue 14: an agent restarted while fixating comes back to the view it held.

// [px] a window of a real aerial photo, at (x, y) of it.
CapturedFrame AerialView(int x, int y, std::uint64_t index) {
  static const cv::Mat photo = kapfix::testing::LoadOpenCvPhoto("aero3.jpg");
  return CapturedFrame{photo(cv::Rect(cv::Point(x, y), kFrame)).clone(),
                       static_cast<std::int64_t>(index) * kFramePeriodUs, index};
}

// A frame with nothing to find (a lens cap, a view the restart lost).
CapturedFrame BlankView(std::uint64_t index) {
  return CapturedFrame{cv::Mat(kFrame, CV_8UC3, cv::Scalar::all(128)),
                       static_cast<std::int64_t>(index) * kFramePeriodUs, index};
}

TEST(ModeRunnerTest, ResumeHoldsTheServosUntilTheStoredViewIsFoundThenFixatesIt) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const CapturedFrame stored = AerialView(300, 200, 3);
  runner.RequestResume(stored.image, 2);
  const ServoTargets servos{3.0, -1.0};
  // The view is not in these frames: the servos hold, nothing is fixated yet.
  for (std::uint64_t i = 0; i < 3; ++i) {
    const FrameOutcome outcome = runner.Process(BlankView(i), servos, 0.033);
    EXPECT_EQ(outcome.mode, AgentMode::kIdle) << i;
    EXPECT_DOUBLE_EQ(outcome.step.targets.pan_deg, servos.pan_deg) << i;
    EXPECT_DOUBLE_EQ(outcome.step.targets.tilt_deg, servos.tilt_deg) << i;
  }
  EXPECT_TRUE(events.resumes.empty());
  // The view is back, 45 px right and 30 px down of where it was: beyond the fixation's
  // search range (24 px), inside the frame.
  const FrameOutcome found = runner.Process(AerialView(255, 170, 3), servos, 0.033);
  EXPECT_EQ(found.mode, AgentMode::kFixate);
  EXPECT_EQ(found.slice, 2);
  EXPECT_EQ(found.patch, SlicePatch(kFrame, kSlices, 2, kPatch));
  ASSERT_TRUE(found.step.match.found);
  EXPECT_NEAR(found.step.match.displacement.x, 45, 1.0);
  EXPECT_NEAR(found.step.match.displacement.y, 30, 1.0);
  // The view held is not the finding frame's: the report judges it from where it was found.
  ASSERT_EQ(found.reference_frame, std::optional<std::uint64_t>(3));
  EXPECT_NEAR(found.reference_seen_at.x, 45, 1.0);
  EXPECT_NEAR(found.reference_seen_at.y, 30, 1.0);
  EXPECT_EQ(events.resumes, std::vector<bool>{true});
  EXPECT_EQ(runner.mode(), AgentMode::kFixate);
  // The loop goes on from there: the next frame, a little further, is still the stored view.
  const FrameOutcome next = runner.Process(AerialView(250, 170, 4), servos, 0.033);
  ASSERT_TRUE(next.step.match.found);
  EXPECT_NEAR(next.step.match.displacement.x, 50, 1.0);
  EXPECT_NEAR(next.step.match.displacement.y, 30, 1.0);
  EXPECT_EQ(next.reference_seen_at, found.reference_seen_at);
}

TEST(ModeRunnerTest, ResumeThatCannotFindTheStoredViewStaysIdleAndSaysSo) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  runner.RequestResume(AerialView(300, 200, 3).image, 2);
  const ServoTargets servos{3.0, -1.0};
  std::uint64_t index = 0;
  while (events.resumes.empty() && index < 1000) {
    const FrameOutcome outcome = runner.Process(BlankView(index++), servos, 0.033);
    EXPECT_EQ(outcome.mode, AgentMode::kIdle);
    EXPECT_DOUBLE_EQ(outcome.step.targets.pan_deg, servos.pan_deg);
    EXPECT_DOUBLE_EQ(outcome.step.targets.tilt_deg, servos.tilt_deg);
  }
  EXPECT_EQ(events.resumes, std::vector<bool>{false});
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);
  // Idle for good: the start mode (fixate) is not taken up behind the operator's back.
  EXPECT_EQ(runner.Process(AerialView(300, 200, index), servos, 0.033).mode, AgentMode::kIdle);
}

TEST(ModeRunnerTest, SspStartedWhileFixatingGoesBackToThePreviousSliceAndReference) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(12, 7);
  Feed(runner, frames[0]);
  runner.RequestSlice(2);
  Feed(runner, frames[1]);
  ASSERT_EQ(runner.mode(), AgentMode::kFixate);
  runner.RequestMode(AgentMode::kSsp, SwingDeadline{8, 100.0});
  std::size_t i = 2;
  while (events.finished_slice_reports() == 0 && i < frames.size()) Feed(runner, frames[i++]);
  ASSERT_EQ(events.finished_slice_reports(), 1);
  EXPECT_EQ(runner.mode(), AgentMode::kFixate);
  EXPECT_EQ(runner.slice(), 2);
  ASSERT_LT(i, frames.size());
  const FrameOutcome after = Feed(runner, frames[i]);
  EXPECT_EQ(after.mode, AgentMode::kFixate);
  EXPECT_EQ(after.slice, 2);
  ASSERT_TRUE(after.reference_frame.has_value());
  EXPECT_EQ(*after.reference_frame, 7u);  // the view held before SSP, not a new one
  EXPECT_EQ(after.patch, SlicePatch(kFrame, kSlices, 2, kPatch));
  ASSERT_TRUE(after.step.match.found);
  const std::vector<int> positions = Positions(12);
  EXPECT_NEAR(after.step.match.displacement.x, -(positions[i] - positions[0]), 0.5);
}

TEST(ModeRunnerTest, SspRestartedWhileRunningStillGoesBackToTheFixationBeforeIt) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(14, 7);
  Feed(runner, frames[0]);
  runner.RequestMode(AgentMode::kSsp, SwingDeadline{8, 100.0});
  Feed(runner, frames[1]);
  Feed(runner, frames[2]);
  runner.RequestMode(AgentMode::kSsp, SwingDeadline{8, 100.0});  // the operator again
  std::size_t i = 3;
  while (events.finished_slice_reports() == 0 && i < frames.size()) Feed(runner, frames[i++]);
  ASSERT_EQ(events.finished_slice_reports(), 1);
  EXPECT_EQ(runner.mode(), AgentMode::kFixate);
  EXPECT_EQ(runner.slice(), (kSlices + 1) / 2);
}

TEST(ModeRunnerTest, SspStartedWhileIdleStillEndsIdle) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(12, 7);
  Feed(runner, frames[0]);
  runner.RequestMode(AgentMode::kIdle);
  Feed(runner, frames[1]);
  runner.RequestMode(AgentMode::kSsp, SwingDeadline{8, 100.0});
  std::size_t i = 2;
  while (events.finished_slice_reports() == 0 && i < frames.size()) Feed(runner, frames[i++]);
  ASSERT_EQ(events.finished_slice_reports(), 1);
  EXPECT_EQ(runner.mode(), AgentMode::kIdle);
}

TEST(ModeRunnerTest, FixateReportsEachNewReference) {
  RecordingModeEvents events;
  ModeRunner runner(SmallConfig(), Options(AgentMode::kFixate), events);
  const std::vector<CapturedFrame> frames = Swing(3);
  Feed(runner, frames[0]);
  Feed(runner, frames[1]);
  EXPECT_EQ(events.references_taken, 1);
  runner.RequestMode(AgentMode::kFixate);
  Feed(runner, frames[2]);
  EXPECT_EQ(events.references_taken, 2);
}

}  // namespace
}  // namespace kapfix::agent
