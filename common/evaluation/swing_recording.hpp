#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "common/image/color_channel.hpp"
#include "common/sim/open_loop_swing.hpp"

namespace kapfix {

// The frames of an open-loop swing (SPEC §3), rendered once and kept as matcher planes with
// their truth, so that several strategies or slices are compared on the very same frames.
struct SwingRecording {
  std::vector<cv::Mat> planes;     // ExtractChannel of each frame
  std::vector<cv::Point2d> truth;  // [px] TrueDisplacement(t, 0): stored-reference truth
  std::vector<cv::Point2d> step;   // [px] TrueDisplacement(t, t − 1); step[0] = 0
  double upscale_factor = 1.0;     // > 1 when the scene had to be enlarged
};

SwingRecording RecordSwing(const cv::Mat& scene_bgr, const SwingOptions& options,
                           ColorChannel channel,
                           const std::function<void(int, int)>& progress = nullptr);

}  // namespace kapfix
