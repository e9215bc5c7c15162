#include "bench/loop_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace kapfix::bench {
namespace {

// One line per frame of a flight: the true view error, the servos' true output angles, what
// the loop believed them to be and what it commanded after the frame, and the measured
// displacement against the true one (−view error), and where the motion alone would have put
// the view (the open loop) — to see where a world's error is made.
void WriteTrace(const std::string& path, const ClosedLoopFigures& f) {
  std::ofstream out(path);
  out << "frame,err_x,err_y,true_pan,true_tilt,believed_pan,believed_tilt,commanded_pan,"
         "commanded_tilt,measured_x,measured_y,confidence,lock_lost,off_target,open_x,open_y,"
         "pan_forecaster,pan_forecast_weight,pan_calibration_ratio,pan_belief_calibration_ratio,"
         "roll_read_deg,roll_true_deg,tilt_forecaster,tilt_forecast_weight,tilt_calibration_ratio,"
         "tilt_belief_calibration_ratio\n";
  for (std::size_t k = 0; k < f.view_offsets.size(); ++k) {
    out << k + 1 << ',' << f.view_offsets[k].x << ',' << f.view_offsets[k].y << ','
        << f.angles[k].pan_deg << ',' << f.angles[k].tilt_deg << ',' << f.believed[k].pan_deg << ','
        << f.believed[k].tilt_deg << ',' << f.commanded[k].pan_deg << ',' << f.commanded[k].tilt_deg
        << ',' << f.measured_x[k] << ',' << f.measured_y[k] << ',' << f.confidence[k] << ','
        << (f.lock_lost[k] ? 1 : 0) << ',' << (f.off_target[k] ? 1 : 0) << ','
        << f.open_offsets[k].x << ',' << f.open_offsets[k].y << ',' << f.pan_forecast[k].forecaster
        << ',' << f.pan_forecast[k].weight << ',' << f.pan_forecast[k].calibration_ratio << ','
        << f.pan_forecast[k].belief_calibration_ratio << ',' << f.roll_read_deg[k] << ','
        << f.roll_true_deg[k] << ',' << f.tilt_forecast[k].forecaster << ','
        << f.tilt_forecast[k].weight << ',' << f.tilt_forecast[k].calibration_ratio << ','
        << f.tilt_forecast[k].belief_calibration_ratio << '\n';
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

// [px] RMS of the view error over the second half of the frames (after the lock-on).
double LateRms(const std::vector<cv::Point2d>& view_offsets) {
  const std::size_t half = view_offsets.size() / 2;
  double sum = 0;
  for (std::size_t k = half; k < view_offsets.size(); ++k) {
    sum += view_offsets[k].dot(view_offsets[k]);
  }
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, view_offsets.size() - half)));
}

void DropPerFrame(ClosedLoopFigures* f) {
  f->view_offsets = {};
  f->open_offsets = {};
  f->pan_forecast = {};
  f->tilt_forecast = {};
  f->measured_x = {};
  f->measured_y = {};
  f->confidence = {};
  f->lock_lost = {};
  f->off_target = {};
  f->angles = {};
  f->believed = {};
  f->commanded = {};
  f->roll_read_deg = {};
  f->roll_true_deg = {};
}

}  // namespace

std::string LoopRun::ProgressLine(std::size_t k, std::size_t total) const {
  char line[256];
  std::snprintf(line, sizeof line, "\r[%zu/%zu] %-9s %-16s %-10s %-11s %4.2f seed %d: %6.2f px   ",
                k, total, world.c_str(), flight.scene.c_str(), flight.controller.c_str(),
                flight.start.c_str(), flight.gain, flight.seed, figures.rms_error_px);
  return line;
}

std::string LoopRun::DetailLine() const {
  const ClosedLoopFigures& f = figures;
  char line[256];
  std::snprintf(line, sizeof line,
                "late %6.2f | x %6.2f y %6.2f | miss %5.2f | forecast %5.1f%% lost %5.1f%% | "
                "open %6.2f floor %5.2f | deg/px ratio %5.3f σ %5.3f%s\n",
                late_rms_error_px, f.rms_error_x_px, f.rms_error_y_px, f.measurement_rms_px,
                f.predicting_pct, f.lock_lost_pct, f.open_loop_rms_px, f.aim_floor_rms_px,
                f.deg_per_px_estimate_ratio, f.deg_per_px_estimate_sigma,
                f.deg_per_px_estimate_trusted ? " trusted" : "");
  return line;
}

std::string LoopRun::TraceFileName() const {
  char gain_text[16];
  std::snprintf(gain_text, sizeof gain_text, "%.2f", flight.gain);
  return "trace_" + world + "_" + flight.scene + "_" + flight.controller + "_" + flight.start +
         "_" + gain_text + "_" + std::to_string(flight.seed) + ".csv";
}

LoopRun Fly(const cv::Mat& scene_bgr, const LoopFlight& flight, const ClosedLoopOptions& agent_loop,
            const LoopWorld& world, int frames, const std::string& trace_dir) {
  LoopRun run{flight, world.name,
              EvaluateClosedLoop(scene_bgr, flight.Options(agent_loop, world.options, frames)),
              0.0};
  run.late_rms_error_px = LateRms(run.figures.view_offsets);
  if (!trace_dir.empty()) WriteTrace(trace_dir + "/" + run.TraceFileName(), run.figures);
  DropPerFrame(&run.figures);
  return run;
}

}  // namespace kapfix::bench
