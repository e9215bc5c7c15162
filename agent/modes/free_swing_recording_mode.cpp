#include "agent/modes/free_swing_recording_mode.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

#include "agent/modes/run_options.hpp"
#include "common/io/atomic_file.hpp"
#include "common/selection/displacement_graph.hpp"

namespace kapfix::agent {

void FreeSwingRecordingMode::Enter(const CapturedFrame& frame, const ServoTargets& current) {
  hold_ = current;
  window_.start_index = frame.index;
  if (context_.options().recordings_dir.empty()) {
    throw std::runtime_error("no recordings folder configured");
  }
  previous_plane_ = context_.Plane(frame.image);
  sample_set_.emplace(std::vector<cv::Rect>{context_.SlicePatchRect(previous_plane_.size())},
                      context_.settings().search.sampling);
}

FrameOutcome FreeSwingRecordingMode::Process(const CapturedFrame& frame,
                                             const ServoTargets& /*current*/, double /*dt_s*/) {
  if (frame.index != window_.start_index) {
    const cv::Mat plane = context_.Plane(frame.image);
    samples_.emplace_back(
        frame.capture_time_us,
        MeasureDisplacement(previous_plane_, plane, *sample_set_, *context_.strategy(),
                            MakeSearchOptions(context_.settings().search)));
    previous_plane_ = plane;
  }
  if (window_.Reached(frame.index)) {
    Write(frame.capture_time_us);
    Finish(ModeEnd{.fixate = std::nullopt, .hold = hold_, .resumed = std::nullopt});
  }
  return context_.Hold(AgentMode::kRecordFreeSwing, hold_);
}

void FreeSwingRecordingMode::Write(std::int64_t capture_time_us) {
  const SearchConfig& search = context_.settings().search;
  std::ostringstream csv;
  csv << "# kapfix free swing: slice " << context_.slice() << " of " << search.slices << ", patch "
      << search.patch_px << " px, axis " << ToString(search.axis)
      << "\ncapture_time_us,displacement_px\n";
  for (const auto& [time_us, displacement] : samples_) {
    csv << time_us << ',' << displacement << '\n';
  }
  const std::string dir = context_.options().recordings_dir;
  const auto name = "free-swing-" + std::to_string(capture_time_us) + ".csv";
  const std::string path = (std::filesystem::path(dir) / name).string();
  const std::size_t samples = samples_.size();
  ModeEvents& events = context_.events();
  // Written (with fsync) by the worker: the control thread never waits for the disk.
  auto write = [dir, path, samples, text = csv.str(), &events]() -> WorkQueue::Result {
    std::string error;
    try {
      std::filesystem::create_directories(dir);
      WriteFileAtomically(path, text);
      spdlog::info("free swing of {} samples recorded to {}", samples, path);
    } catch (const std::exception& e) {
      error = e.what();
      spdlog::error("free swing not recorded: {}", error);
    }
    return [&events, path, error] { events.OnFreeSwingRecorded(path, error); };
  };
  std::string refused;
  if (!context_.worker().Post("free swing recording " + path, std::move(write), &refused)) {
    events.OnFreeSwingRecorded(path, refused);
  }
  samples_.clear();
}

}  // namespace kapfix::agent
