#include "agent/modes/mode_runner.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "agent/config/options_from_settings.hpp"
#include "agent/modes/report_messages.hpp"
#include "common/control/controller_factory.hpp"
#include "common/image/color_channel.hpp"
#include "common/io/atomic_file.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sample_set.hpp"
#include "common/selection/displacement_graph.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix::agent {
namespace {

// Whether two settings build the same fixation loop (Rebuild's inputs: search, controller
// kind, active lens) but for the controller's gains, which the loop takes without a rebuild.
// A setting re-sent unchanged, or new gains, must not reset the controller (issue 15, item 7).
bool SameLoop(const AgentConfig& a, const AgentConfig& b) {
  const SearchConfig& s = a.search;
  const SearchConfig& t = b.search;
  const LensProfile& l = a.active_lens();
  const LensProfile& m = b.active_lens();
  return s.strategy == t.strategy && ToString(s.sampling) == ToString(t.sampling) &&
         s.sampling.seed == t.sampling.seed && s.patch_px == t.patch_px && s.slices == t.slices &&
         s.axis == t.axis && s.range_px == t.range_px && s.channel == t.channel &&
         s.subpixel == t.subpixel && s.slice_score == t.slice_score &&
         s.dc_hysteresis_px == t.dc_hysteresis_px && a.gains.controller() == b.gains.controller() &&
         l.name == m.name && l.DegPerPxPan() == m.DegPerPxPan() &&
         l.DegPerPxTilt() == m.DegPerPxTilt();
}

// Progress reports of a free-swing process every this many frames (and at its end): often
// enough for a live progress bar, rare enough not to flood the link with graphs.
constexpr std::uint64_t kProgressEveryFrames = 5;
// [px] each calibration move shifts the view by about this much at the lens's current deg/px:
// large against the matcher's noise, well inside its search range.
constexpr double kCalibrationSpanPx = 30.0;
constexpr int kCalibrationStepsPerSide = 5;
constexpr std::array<int, 3> kPatchSizeCandidates{50, 100, 150};  // [px] the thesis's
// [frames] a resuming agent searches for its stored view this long (about a second, so a
// swing that carried it out of the frame brings it back) before it gives up and stays idle.
constexpr int kResumeFrames = 30;
// The whole-frame search of a resume: the hierarchical strategy, whatever the fixation
// uses, so a frame-wide window costs about what the exhaustive one does on ±range.
constexpr const char* kResumeStrategy = "pyr";

SearchOptions MakeSearchOptions(const SearchConfig& search) {
  SearchOptions o;
  o.axis = search.axis;
  o.range = search.range_px;
  o.cross_range = std::min(o.cross_range, search.range_px);
  o.subpixel = search.subpixel;
  return o;
}

}  // namespace

ModeRunner::ModeRunner(std::shared_ptr<const AgentConfig> settings, ModeRunnerOptions options,
                       ModeEvents& events)
    : options_(std::move(options)), events_(events), settings_(std::move(settings)) {
  slice_ = (settings_->search.slices + 1) / 2;
  Rebuild();
  pending_.mode = std::make_pair(options_.start_mode, options_.default_deadline);
}

void ModeRunner::RequestMode(AgentMode mode, std::optional<SwingDeadline> deadline) {
  std::lock_guard lock(pending_mutex_);
  pending_.mode = std::make_pair(mode, deadline.value_or(options_.default_deadline));
}

void ModeRunner::RequestSettings(std::shared_ptr<const AgentConfig> settings) {
  std::lock_guard lock(pending_mutex_);
  pending_.settings = std::move(settings);
}

void ModeRunner::RequestSlice(int slice) {
  std::lock_guard lock(pending_mutex_);
  pending_.slice = slice;
}

void ModeRunner::RequestResume(cv::Mat reference_frame_bgr, int slice) {
  std::lock_guard lock(pending_mutex_);
  pending_.resume = std::make_pair(std::move(reference_frame_bgr), slice);
  pending_.mode.reset();  // the resume decides: fixate when the view is found, else idle
}

FixationOptions ModeRunner::MakeFixationOptions(AgentMode mode) const {
  FixationOptions o;
  o.search = MakeSearchOptions(settings_->search);
  o.sampling = settings_->search.sampling;
  o.channel = settings_->search.channel;
  o.patch_size = settings_->search.patch_px;
  o.slice_count = settings_->search.slices;
  o.slice = slice_;
  o.reference = mode == AgentMode::kFollow ? FixationOptions::Reference::kPrevious
                                           : FixationOptions::Reference::kStored;
  return o;
}

void ModeRunner::Rebuild() {
  std::string error;
  std::shared_ptr<const SearchStrategy> strategy =
      MakeSearchStrategy(settings_->search.strategy, &error);
  if (!strategy) throw std::runtime_error("search: " + error);
  const LensProfile& lens = settings_->active_lens();
  const LensCalibration calibration{lens.DegPerPxPan(), lens.DegPerPxTilt()};
  std::unique_ptr<Controller> controller =
      MakeController(kapfix::v1::WordOf(settings_->gains.controller()),
                     OptionsFromSettings<ControllerGains>(settings_->gains), calibration,
                     options_.predictive, &error);
  if (!controller) throw std::runtime_error("controller: " + error);
  strategy_ = std::move(strategy);
  loop_ = std::make_unique<FixationLoop>(MakeFixationOptions(mode_), strategy_,
                                         std::move(controller), calibration);
  // The view to hold is the one the operator fixated, not the one in front of the camera
  // when a setting changed.
  if (!reference_frame_.empty()) loop_->SetReference(reference_frame_);
}

void ModeRunner::SetMode(AgentMode mode) {
  mode_ = mode;
  events_.OnModeChanged(mode, slice_);
}

void ModeRunner::ApplyPending(const CapturedFrame& frame, const ServoTargets& current) {
  Pending pending;
  {
    std::lock_guard lock(pending_mutex_);
    std::swap(pending, pending_);
  }
  bool rebuild = false;
  if (pending.resume) {
    slice_ = std::clamp(pending.resume->second, 1, settings_->search.slices);
    resume_ =
        Resume{.reference_frame = std::move(pending.resume->first), .frames_left = kResumeFrames};
    hold_ = current;  // no servo moves until the view is found
    spdlog::info(
        "resuming: searching the whole frame for the view of slice {} held before the "
        "restart; the servos hold until it is found",
        slice_.load());
  }
  if (pending.settings) {
    rebuild = !SameLoop(*settings_, *pending.settings);
    settings_ = std::move(pending.settings);
    slice_ = std::clamp(slice_.load(), 1, settings_->search.slices);
  }
  if (pending.slice || pending.mode) resume_.reset();  // the operator decides instead
  if (pending.slice) {
    // Picking a slice means fixating on it (the operator confirms SSP's choice or overrides
    // it): a fixation in progress keeps its reference frame and moves to the new patch; any
    // other mode hands over to fixate.
    slice_ = std::clamp(*pending.slice, 1, settings_->search.slices);
    rebuild = true;
    const AgentMode now = mode_;
    if (!pending.mode && now != AgentMode::kFixate && now != AgentMode::kFollow) {
      pending.mode = std::make_pair(AgentMode::kFixate, options_.default_deadline);
    } else {
      events_.OnModeChanged(now, slice_);
    }
  }
  try {
    if (rebuild) {
      Rebuild();
    } else if (pending.settings && loop_) {
      // Bumpless: the controller keeps its state.
      loop_->SetGains(OptionsFromSettings<ControllerGains>(settings_->gains));
    }
    if (pending.mode) Enter(pending.mode->first, pending.mode->second, frame, current);
  } catch (const std::exception& e) {
    // A setting that cannot work with this camera (a patch larger than the frame) or a
    // strategy that cannot be built: hold still and say why rather than fly blind.
    spdlog::error("cannot {}: {}; the agent is idle",
                  pending.mode ? std::string(ToString(pending.mode->first)) : "apply settings",
                  e.what());
    reference_frame_.release();
    slice_run_.reset();
    pss_run_.reset();
    calibration_.reset();
    hold_ = current;
    SetMode(AgentMode::kIdle);
  }
}

cv::Rect ModeRunner::SlicePatchRect(cv::Size frame) const {
  return SlicePatch(frame, settings_->search.slices, slice_, settings_->search.patch_px);
}

void ModeRunner::Enter(AgentMode mode, const SwingDeadline& deadline, const CapturedFrame& frame,
                       const ServoTargets& current) {
  // SSP started while fixating keeps that fixation to go back to (SSP restarted keeps it
  // too); anything else drops it.
  if (mode == AgentMode::kSsp && mode_ == AgentMode::kFixate && !reference_frame_.empty()) {
    held_fixation_ = HeldFixation{reference_frame_, reference_index_, slice_.load()};
  } else if (mode != AgentMode::kSsp || mode_ != AgentMode::kSsp) {
    held_fixation_.reset();
  }
  slice_run_.reset();
  pss_run_.reset();
  calibration_.reset();
  recording_.clear();
  recording_samples_.reset();
  hold_ = current;
  deadline_ = deadline;
  swing_start_index_ = frame.index;
  mode_ = mode;
  const auto needs_plane = mode == AgentMode::kSsp || mode == AgentMode::kPss ||
                           mode == AgentMode::kCalibrate || mode == AgentMode::kRecordFreeSwing;
  const cv::Mat plane =
      needs_plane ? ExtractChannel(frame.image, settings_->search.channel) : cv::Mat();
  switch (mode) {
    case AgentMode::kIdle:
      reference_frame_.release();
      break;
    case AgentMode::kFixate:
    case AgentMode::kFollow:
      reference_frame_ = frame.image.clone();
      reference_index_ = frame.index;
      Rebuild();
      if (mode == AgentMode::kFixate) events_.OnReferenceTaken(reference_frame_, current);
      break;
    case AgentMode::kSsp: {
      reference_frame_.release();
      SliceSelectionOptions o;
      o.slice_count = settings_->search.slices;
      o.patch_size = settings_->search.patch_px;
      o.sampling = settings_->search.sampling;
      o.search = MakeSearchOptions(settings_->search);
      o.hysteresis_px = settings_->search.dc_hysteresis_px;
      o.score = settings_->search.slice_score;
      run_strategy_ = strategy_;
      slice_run_.emplace(plane, *run_strategy_, o);
      break;
    }
    case AgentMode::kPss: {
      reference_frame_.release();
      PatchSizeSelectionOptions o;
      o.sizes.clear();
      for (const int size : kPatchSizeCandidates) {
        if (size <= std::min(plane.cols, plane.rows)) o.sizes.push_back(size);
      }
      o.sampling = settings_->search.sampling;
      o.search = MakeSearchOptions(settings_->search);
      run_strategy_ = strategy_;
      pss_run_.emplace(plane, *run_strategy_, o);
      break;
    }
    case AgentMode::kCalibrate: {
      reference_frame_.release();
      const LensProfile& lens = settings_->active_lens();
      CalibrationRunOptions o;
      o.span_deg = kCalibrationSpanPx * std::max(lens.DegPerPxPan(), lens.DegPerPxTilt());
      o.step_deg = o.span_deg / kCalibrationStepsPerSide;
      o.settle_frames = options_.actuation_delay_frames + 1;
      o.patch = SlicePatchRect(plane.size());
      o.sampling = settings_->search.sampling;
      o.search = MakeSearchOptions(settings_->search);
      o.park = current;
      run_strategy_ = strategy_;
      calibration_.emplace(o, *run_strategy_);
      break;
    }
    case AgentMode::kRecordFreeSwing:
      reference_frame_.release();
      if (options_.recordings_dir.empty()) {
        throw std::runtime_error("no recordings folder configured");
      }
      previous_plane_ = plane;
      recording_samples_.emplace(std::vector<cv::Rect>{SlicePatchRect(plane.size())},
                                 settings_->search.sampling);
      break;
  }
  spdlog::info("mode {}{}", ToString(mode),
               mode == AgentMode::kFixate || mode == AgentMode::kFollow
                   ? " on slice " + std::to_string(slice_.load())
                   : std::string());
  SetMode(mode);
}

bool ModeRunner::SwingDeadlineReached(std::uint64_t index) const {
  const auto frames = static_cast<double>(index - swing_start_index_ + 1);
  return frames >= deadline_.frames || (frames - 1) * options_.frame_period_s >= deadline_.seconds;
}

FrameOutcome ModeRunner::Hold(AgentMode mode) const {
  FrameOutcome outcome;
  outcome.step.targets = hold_;
  outcome.mode = mode;
  outcome.slice = slice_;
  outcome.slice_count = settings_->search.slices;
  return outcome;
}

FrameOutcome ModeRunner::Process(const CapturedFrame& frame, const ServoTargets& current,
                                 double dt_s) {
  ApplyPending(frame, current);
  if (resume_) return ResumeSearch(frame, current, dt_s);
  switch (mode_.load()) {
    case AgentMode::kIdle:
      return Hold(AgentMode::kIdle);
    case AgentMode::kFixate:
    case AgentMode::kFollow:
      return Fixate(frame, current, dt_s);
    case AgentMode::kSsp:
      return SelectSlice(ExtractChannel(frame.image, settings_->search.channel), frame.index);
    case AgentMode::kPss:
      return SelectPatchSize(ExtractChannel(frame.image, settings_->search.channel), frame.index);
    case AgentMode::kCalibrate:
      return Calibrate(ExtractChannel(frame.image, settings_->search.channel));
    case AgentMode::kRecordFreeSwing:
      return RecordFreeSwing(ExtractChannel(frame.image, settings_->search.channel), frame);
  }
  return Hold(mode_);
}

FrameOutcome ModeRunner::Fixate(const CapturedFrame& frame, const ServoTargets& current,
                                double dt_s) {
  FrameOutcome outcome;
  outcome.step = loop_->Process(frame.image, current, dt_s);
  // The operator must hear of a lock the agent does not trust (issue 9), once per change;
  // telemetry carries it on every frame as lock_lost.
  if (outcome.step.lock_lost != lock_lost_) {
    lock_lost_ = outcome.step.lock_lost;
    if (lock_lost_) {
      spdlog::warn(
          "frame {}: match not trusted (confidence {:.2f}, ambiguous or poor): re-acquiring the "
          "stored reference; the servos follow the forecast swing, then hold",
          frame.index, outcome.step.match.confidence);
    } else {
      spdlog::info("frame {}: stored reference re-acquired, lock trusted again", frame.index);
    }
  }
  outcome.mode = mode_;
  outcome.slice = slice_;
  outcome.slice_count = settings_->search.slices;
  outcome.patch = loop_->patch();
  if (mode_ == AgentMode::kFixate) outcome.reference_frame = reference_index_;
  return outcome;
}

FrameOutcome ModeRunner::ResumeSearch(const CapturedFrame& frame, const ServoTargets& current,
                                      double dt_s) {
  FrameOutcome outcome = Hold(AgentMode::kIdle);
  outcome.step.lock_lost = true;
  std::string error;
  const std::unique_ptr<SearchStrategy> strategy = MakeSearchStrategy(kResumeStrategy, &error);
  const cv::Mat stored = ExtractChannel(resume_->reference_frame, settings_->search.channel);
  const cv::Mat plane = ExtractChannel(frame.image, settings_->search.channel);
  const FixationOptions fixation = MakeFixationOptions(AgentMode::kFixate);
  if (strategy && stored.size() == plane.size() && stored.type() == plane.type()) {
    const cv::Rect patch = SlicePatchRect(stored.size());
    const ReferencePatch reference(stored, SampleSet({patch}, settings_->search.sampling));
    SearchOptions wide = MakeSearchOptions(settings_->search);
    wide.axis = SearchAxis::kBoth;  // wherever the restart left the view
    wide.range = std::max(plane.cols, plane.rows);
    wide.origin = {0, 0};
    outcome.step.match = strategy->Search(reference, plane, wide);
  } else {
    resume_->frames_left = 0;  // another camera or frame size: the view cannot be compared
    if (error.empty()) {
      error = fmt::format("the stored reference is {}x{} px, the camera's frames {}x{} px",
                          stored.cols, stored.rows, plane.cols, plane.rows);
    }
  }
  const SearchResult& match = outcome.step.match;
  if (match.found && match.confidence >= fixation.lock_lost_confidence) {
    // Found: the stored view becomes the reference and the loop closes from where it is.
    reference_frame_ = resume_->reference_frame;
    reference_index_ = frame.index;
    resume_.reset();
    mode_ = AgentMode::kFixate;
    try {
      Rebuild();
    } catch (const std::exception& e) {
      spdlog::error("not resumed: {}; the agent is idle", e.what());
      reference_frame_.release();
      mode_ = AgentMode::kIdle;
      SetMode(AgentMode::kIdle);
      events_.OnResumeEnded(false);
      return outcome;
    }
    loop_->SeekFrom(match.shift);
    spdlog::info(
        "resumed: the view of slice {} held before the restart found at ({}, {}) px, confidence "
        "{:.2f}; fixating it",
        slice_.load(), match.shift.x, match.shift.y, match.confidence);
    SetMode(AgentMode::kFixate);
    events_.OnResumeEnded(true);
    return Fixate(frame, current, dt_s);
  }
  if (match.found) resume_->best_confidence = std::max(resume_->best_confidence, match.confidence);
  if (--resume_->frames_left > 0) return outcome;
  if (error.empty()) {
    error = fmt::format("best confidence {:.2f} in {} frames, below {:.2f}",
                        resume_->best_confidence, kResumeFrames, fixation.lock_lost_confidence);
  }
  spdlog::warn(
      "not resumed: the view of slice {} held before the restart was not found ({}); the agent "
      "stays idle: run SSP or select a slice to fixate",
      slice_.load(), error);
  resume_.reset();
  SetMode(AgentMode::kIdle);
  events_.OnResumeEnded(false);
  return outcome;
}

SwingProgress ModeRunner::ProgressOf(int frames_used, bool done) const {
  SwingProgress progress;
  progress.done = frames_used;
  progress.total = deadline_.frames;
  progress.finished = done;
  progress.deadline_reached = done && frames_used < deadline_.frames;
  return progress;
}

FrameOutcome ModeRunner::SelectSlice(const cv::Mat& plane, std::uint64_t index) {
  if (index != swing_start_index_) slice_run_->AddFrame(plane);
  const bool done = SwingDeadlineReached(index);
  const int used = slice_run_->frames_used();
  if (done || used % kProgressEveryFrames == 0) {
    const SwingProgress progress = ProgressOf(used, done);
    const SliceSelection selection = slice_run_->Result(progress.deadline_reached);
    SliceReportContext context;
    context.score = settings_->search.slice_score;
    context.hysteresis_px = settings_->search.dc_hysteresis_px;
    context.patch_size_px = settings_->search.patch_px;
    context.strategy = settings_->search.strategy;
    events_.OnSliceReport(MakeSliceReport(selection, context, progress));
    if (done) {
      // The recommended slice becomes the one in use; the operator confirms it (or picks
      // another) and starts fixating.
      slice_run_.reset();
      if (held_fixation_) {
        // The view fixated before SSP is held again until the operator confirms a slice
        // (select_slice): SSP alone never drops the lock.
        reference_frame_ = held_fixation_->reference_frame;
        reference_index_ = held_fixation_->reference_index;
        slice_ = held_fixation_->slice;
        held_fixation_.reset();
        mode_ = AgentMode::kFixate;
        Rebuild();
        spdlog::info(
            "SSP finished after {} frames: slice {} recommended; fixating slice {} again until "
            "a slice is confirmed",
            used, selection.best_slice, slice_.load());
        SetMode(AgentMode::kFixate);
      } else {
        slice_ = selection.best_slice;
        spdlog::info("SSP finished after {} frames: slice {} recommended", used,
                     selection.best_slice);
        SetMode(AgentMode::kIdle);
      }
    }
  }
  return Hold(AgentMode::kSsp);
}

FrameOutcome ModeRunner::SelectPatchSize(const cv::Mat& plane, std::uint64_t index) {
  if (index != swing_start_index_) pss_run_->AddFrame(plane);
  const bool done = SwingDeadlineReached(index);
  const int used = pss_run_->frames_used();
  if (done || used % kProgressEveryFrames == 0) {
    const SwingProgress progress = ProgressOf(used, done);
    const PatchSizeSelection selection = pss_run_->Result();
    events_.OnPssReport(MakePssReport(selection, pss_run_->graphs(), progress));
    if (done) {
      pss_run_.reset();
      spdlog::info("PSS finished after {} frames: {} px recommended", used, selection.best_size);
      SetMode(AgentMode::kIdle);
    }
  }
  return Hold(AgentMode::kPss);
}

FrameOutcome ModeRunner::Calibrate(const cv::Mat& plane) {
  FrameOutcome outcome = Hold(AgentMode::kCalibrate);
  outcome.step.targets = calibration_->Step(plane);
  const std::string lens = settings_->lens;  // a copy: settings_ is replaced below
  if (!calibration_->finished()) {
    if (calibration_->moves_done() != calibration_progress_) {
      calibration_progress_ = calibration_->moves_done();
      events_.OnCalibrationReport(
          MakeCalibrationReport(lens, std::nullopt, std::nullopt, calibration_->moves_done(),
                                calibration_->moves_total(), false),
          std::nullopt);
    }
    return outcome;
  }
  std::optional<AxisCalibration> pan;
  std::optional<AxisCalibration> tilt;
  std::optional<LensCalibration> applied;
  try {
    pan = calibration_->FitPan();
    tilt = calibration_->FitTilt();
  } catch (const std::invalid_argument& e) {
    spdlog::error("calibration failed, the lens keeps its deg/px: {}", e.what());
  }
  if (pan && tilt) {
    const LensCalibration fitted = LensCalibration::FromCalibrationMoves(*pan, *tilt);
    std::string error;
    if (fitted.IsValid(&error)) {
      auto calibrated = std::make_shared<AgentConfig>(*settings_);
      calibrated->ApplyLensCalibration(lens, fitted);
      settings_ = std::move(calibrated);
      loop_->SetCalibration(fitted);
      applied = fitted;
      spdlog::info(
          "calibrated lens {}: pan {:.5f} deg/px (residual {:.2f} px), tilt {:.5f} "
          "deg/px (residual {:.2f} px)",
          lens, fitted.pan_deg_per_px, pan->residual_px, fitted.tilt_deg_per_px, tilt->residual_px);
    } else {
      spdlog::error("calibration gave an unusable fit, the lens keeps its deg/px: {}", error);
    }
  }
  events_.OnCalibrationReport(MakeCalibrationReport(lens, pan, tilt, calibration_->moves_done(),
                                                    calibration_->moves_total(), true),
                              applied);
  calibration_.reset();
  calibration_progress_ = -1;
  SetMode(AgentMode::kIdle);
  return outcome;
}

FrameOutcome ModeRunner::RecordFreeSwing(const cv::Mat& plane, const CapturedFrame& frame) {
  if (frame.index != swing_start_index_) {
    const SearchStrategy& strategy = *strategy_;
    recording_.emplace_back(frame.capture_time_us,
                            MeasureDisplacement(previous_plane_, plane, *recording_samples_,
                                                strategy, MakeSearchOptions(settings_->search)));
    previous_plane_ = plane;
  }
  if (!SwingDeadlineReached(frame.index)) return Hold(AgentMode::kRecordFreeSwing);

  std::ostringstream csv;
  csv << "# kapfix free swing: slice " << slice_ << " of " << settings_->search.slices << ", patch "
      << settings_->search.patch_px << " px, axis " << ToString(settings_->search.axis)
      << "\ncapture_time_us,displacement_px\n";
  for (const auto& [time_us, displacement] : recording_) {
    csv << time_us << ',' << displacement << '\n';
  }
  const auto name = "free-swing-" + std::to_string(frame.capture_time_us) + ".csv";
  const std::filesystem::path path = std::filesystem::path(options_.recordings_dir) / name;
  std::string error;
  try {
    std::filesystem::create_directories(options_.recordings_dir);
    WriteFileAtomically(path, csv.str());
    spdlog::info("free swing of {} samples recorded to {}", recording_.size(), path.string());
  } catch (const std::exception& e) {
    error = e.what();
    spdlog::error("free swing not recorded: {}", error);
  }
  events_.OnFreeSwingRecorded(path.string(), error);
  recording_.clear();
  recording_samples_.reset();
  SetMode(AgentMode::kIdle);
  return Hold(AgentMode::kRecordFreeSwing);
}

}  // namespace kapfix::agent
