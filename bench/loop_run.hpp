#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>

#include "bench/loop_plan.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"

namespace kapfix::bench {

// One flight of the loop benchmark and its figures.
struct LoopRun {
  LoopFlight flight;
  std::string world;  // the world's name
  // EvaluateClosedLoop's figures without the per-frame vectors (1,300 flights would keep
  // ~100 MB of them): those go to the trace, if asked, before they are dropped.
  ClosedLoopFigures figures;
  double late_rms_error_px = 0;  // [px] RMS view error over the flight's second half

  // "[k/total] world scene controller start gain seed: RMS px", padded to overwrite the
  // previous progress line.
  std::string ProgressLine(std::size_t k, std::size_t total) const;
  // The late RMS, x/y RMS, the matcher's miss, forecast and lost shares, open-loop RMS, the
  // aim floor and the deg/px estimate, for --detail.
  std::string DetailLine() const;
  // trace_WORLD_SCENE_CONTROLLER_START_GAIN_SEED.csv
  std::string TraceFileName() const;
};

// Flies `flight` over `scene_bgr` in `world`, `frames` frames after the reference, from the
// agent's loop `agent_loop` (LoopFlight::Options). With a
// non-empty trace_dir, writes the flight's per-frame trace there (TraceFileName): view error,
// the servos' true, believed and commanded angles, the measured displacement, lock and
// off-target flags, the open-loop offset. Shares nothing mutable with another Fly: flights may run
// in parallel.
LoopRun Fly(const cv::Mat& scene_bgr, const LoopFlight& flight, const ClosedLoopOptions& agent_loop,
            const LoopWorld& world, int frames, const std::string& trace_dir);

}  // namespace kapfix::bench
