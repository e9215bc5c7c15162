#include "common/evaluation/swing_recording.hpp"

namespace kapfix {

SwingRecording RecordSwing(const cv::Mat& scene_bgr, const SwingOptions& options,
                           ColorChannel channel, const std::function<void(int, int)>& progress) {
  const OpenLoopSwing swing(scene_bgr, options);
  SwingRecording recording;
  recording.upscale_factor = swing.camera().upscale_factor();
  const int frames = swing.frames();
  recording.planes.reserve(static_cast<std::size_t>(frames));
  for (int t = 0; t < frames; ++t) {
    recording.planes.push_back(ExtractChannel(swing.Frame(t), channel));
    recording.truth.push_back(swing.TrueDisplacement(t, 0));
    recording.step.push_back(t == 0 ? cv::Point2d(0, 0) : swing.TrueDisplacement(t, t - 1));
    if (progress) progress(t + 1, frames);
  }
  return recording;
}

}  // namespace kapfix
