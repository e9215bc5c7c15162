#include "bench/loop_plan.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "common/analysis/statistics.hpp"

namespace kapfix::bench {
namespace {

// [s] CPU time of one simulated frame and of one flight's set-up, measured on the project's
// 2-core machine (session 11, `--jobs 2`, nice, the agent's built-in loop with its 640×480
// frames): 552 flights of 500 frames (4 worlds, 10 scenes, 3 seeds, both starts, predictive
// and P, with a 72-flight sweep), 240 of them after SSP's 300-frame free swing, took 19.5 min:
// 6.0 ms per fixated frame if a free-swing frame costs 1.6 × as much (SSP scores every slice,
// as measured in session 8). The cost grows with the frame's area (rendering the simulated
// view): session 8's 300×300 frames cost 1.76 ms, 3.4 × less for 3.4 × fewer pixels. A job per
// core turns CPU time into wall-clock time; other load stretches it.
constexpr double kSecondsPerFixatedFrame = 0.0060;
constexpr double kSecondsPerSspFrame = 0.0095;
constexpr double kMeasuredFrameArea = 640.0 * 480.0;  // [px²] of those figures
constexpr double kSecondsPerFlight = 0.005;

bool Known(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::vector<LoopWorld> LoopWorlds() {
  const WorldOptions realistic = WorldOptions::Realistic();
  std::vector<LoopWorld> worlds;
  const auto alone = [&worlds](const std::string& name, auto&& turn_on) {
    WorldOptions w;
    turn_on(w);
    worlds.push_back({name, w});
  };
  worlds.push_back({"nominal", WorldOptions::Nominal()});
  alone("broadband", [](WorldOptions& w) { w.gusts = WorldOptions::Gusts::kBroadband; });
  alone("drift", [&](WorldOptions& w) { w.period_drift = realistic.period_drift; });
  alone("sway", [](WorldOptions& w) { w.sway = true; });
  alone("roll", [&](WorldOptions& w) { w.roll_deg = realistic.roll_deg; });
  alone("blur", [](WorldOptions& w) { w.blur = true; });
  alone("exposure", [](WorldOptions& w) { w.exposure_steps = true; });
  alone("jitter", [&](WorldOptions& w) { w.latency_jitter = realistic.latency_jitter; });
  alone("drops", [&](WorldOptions& w) { w.frame_drops = realistic.frame_drops; });
  alone("calib0.6", [](WorldOptions& w) { w.calibration_error = 0.6; });
  alone("calib1.6", [](WorldOptions& w) { w.calibration_error = 1.6; });
  worlds.push_back({"realistic", realistic});
  return worlds;
}

ClosedLoopOptions LoopFlight::Options(const ClosedLoopOptions& agent_loop,
                                      const WorldOptions& world_options, int frames) const {
  ClosedLoopOptions o = agent_loop;
  o.frames = frames;
  o.start = start == "ssp"      ? ClosedLoopOptions::Start::kAfterSsp
            : start == "moving" ? ClosedLoopOptions::Start::kMoving
                                : ClosedLoopOptions::Start::kFirstFrame;
  o.world = world_options;
  o.controller = controller;
  if (controller != "predictive") {  // the default controller keeps the configured gains
    o.gains.p = gain;
    o.gains.i = 0;
    o.gains.d = 0;
  }
  if (controller == "pid") {
    // A PID as an operator would set it: the P gain plus a little integral and derivative.
    o.gains.i = 0.5;
    o.gains.d = 0.01;
  }
  o.platform.kite.seed = static_cast<std::uint32_t>(seed);
  o.platform.boat.seed = static_cast<std::uint32_t>(seed);
  o.platform.camera.seed = static_cast<std::uint32_t>(seed);
  return o;
}

bool LoopPlan::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (frames < 1 || seeds < 1) return fail("frames and seeds must be ≥ 1");
  if (scenes.empty() || worlds.empty() || controllers.empty() || starts.empty()) {
    return fail("the plan needs at least one scene, world, controller and start");
  }
  if (!Known(controllers, "p")) return fail("controller p (the baseline) is missing");
  if (!agent_loop.IsValid(error)) return false;
  for (const std::string& start : starts) {
    if (start != "first-frame" && start != "ssp" && start != "moving") {
      return fail("unknown start '" + start + "' (first-frame, ssp or moving)");
    }
  }
  if (sweep_gains.empty() || sweep_scenes < 1 || sweep_scenes > static_cast<int>(scenes.size())) {
    return fail("the P-gain sweep needs gains and 1…" + std::to_string(scenes.size()) +
                " scenes, got " + std::to_string(sweep_scenes));
  }
  return true;
}

std::vector<LoopFlight> LoopPlan::SweepFlights() const {
  std::vector<LoopFlight> flights;
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    for (const double gain : sweep_gains) {
      for (int s = 0; s < sweep_scenes; ++s) {
        flights.push_back({scenes[static_cast<std::size_t>(s)], w, "p", "first-frame", gain, 1});
      }
    }
  }
  return flights;
}

std::vector<LoopFlight> LoopPlan::MainFlights(
    const std::map<std::string, double>& best_gain) const {
  std::vector<LoopFlight> flights;
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    const double gain = best_gain.at(worlds[w].name);
    for (const std::string& start : starts) {
      for (const std::string& scene : scenes) {
        for (int seed = 1; seed <= seeds; ++seed) {
          // P at its best gain is what the others are compared with (issue 9); PID starts
          // from the same gain.
          for (const std::string& controller : controllers) {
            flights.push_back({scene, w, controller, start, gain, seed});
          }
        }
      }
    }
  }
  return flights;
}

std::size_t LoopPlan::SweepCount() const {
  return worlds.size() * sweep_gains.size() * static_cast<std::size_t>(sweep_scenes);
}

std::size_t LoopPlan::MainCount() const {
  return worlds.size() * starts.size() * scenes.size() * static_cast<std::size_t>(seeds) *
         controllers.size();
}

double LoopPlan::EstimatedSeconds(int jobs, int cores) const {
  const cv::Size frame = agent_loop.platform.camera.frame_size;
  const double area = static_cast<double>(frame.width) * frame.height / kMeasuredFrameArea;
  const double per_flight = kSecondsPerFlight + kSecondsPerFixatedFrame * area * frames;
  const double ssp_flights = static_cast<double>(MainCount()) *
                             static_cast<double>(std::count(starts.begin(), starts.end(), "ssp")) /
                             static_cast<double>(starts.size());
  const double ssp_frames = agent_loop.ssp_frames;
  const double busy = static_cast<double>(SweepCount() + MainCount()) * per_flight +
                      ssp_flights * ssp_frames * kSecondsPerSspFrame * area;
  // Flights beyond the cores share them; a job per core is the most that helps.
  return busy / std::max(1, std::min(jobs, cores));
}

std::string LoopPlan::DescribeAgentLoop() const {
  const ClosedLoopOptions& a = agent_loop;
  // The gains by their settings' names (ControllerGains::VisitFields), so that a gain added
  // there shows here without being named here.
  std::string gains;
  ControllerGains copy = a.gains;
  copy.VisitFields([&gains](const char* name, double value) {
    char field[64];
    std::snprintf(field, sizeof field, "%s%s %g", gains.empty() ? "" : ", ", name, value);
    gains += field;
  });
  char line[320];
  std::snprintf(line, sizeof line,
                "the agent's loop: %s controller (%s); %.0f frames/s; servos %.1f deg/frame; %s "
                "search on a %d px patch; SSP's free swing %d frames\n",
                a.controller.c_str(), gains.c_str(), 1.0 / a.frame_period_s,
                a.platform.pan.rate_limit_deg_per_frame, a.strategy.c_str(), a.fixation.patch_size,
                a.ssp_frames);
  std::string text = line;
  if (!world_scale_note.empty()) text += "note: " + world_scale_note + "\n";
  return text;
}

std::string LoopPlan::Describe(int jobs, int cores) const {
  char line[256];
  std::string text = DescribeAgentLoop();
  std::snprintf(line, sizeof line,
                "P-gain sweep: %zu worlds × %zu gains × %d scenes (seed 1, first-frame) = %zu "
                "flights\n",
                worlds.size(), sweep_gains.size(), sweep_scenes, SweepCount());
  text += line;
  std::snprintf(line, sizeof line,
                "main: %zu worlds × %zu starts × %zu scenes × %d seeds × %zu controllers = %zu "
                "flights\n",
                worlds.size(), starts.size(), scenes.size(), seeds, controllers.size(),
                MainCount());
  text += line;
  const std::size_t per_controller = MainCount() / controllers.size();
  for (const std::string& controller : controllers) {
    std::snprintf(line, sizeof line, "  %-10s %zu flights%s\n", controller.c_str(),
                  per_controller + (controller == "p" ? SweepCount() : 0),
                  controller == "p" ? " (the sweep's included)" : "");
    text += line;
  }
  for (const std::string& start : starts) {
    std::snprintf(line, sizeof line, "  %-10s %zu flights%s\n", start.c_str(),
                  MainCount() / starts.size() + (start == "first-frame" ? SweepCount() : 0),
                  start == "ssp" ? " (each after SSP's free swing)" : "");
    text += line;
  }
  const double minutes = EstimatedSeconds(jobs, cores) / 60.0;
  std::snprintf(line, sizeof line, "%zu flights of %d frames, about %.0f min at --jobs %d\n",
                SweepCount() + MainCount(), frames, std::max(1.0, minutes), jobs);
  text += line;
  return text;
}

std::map<std::string, double> BestGains(const LoopPlan& plan, const std::vector<LoopFlight>& sweep,
                                        const std::vector<double>& rms_error_px) {
  std::map<std::string, double> best_gain;
  for (std::size_t w = 0; w < plan.worlds.size(); ++w) {
    double best = std::numeric_limits<double>::infinity();
    best_gain[plan.worlds[w].name] = plan.sweep_gains.front();  // should every median be NaN
    for (const double gain : plan.sweep_gains) {
      std::vector<double> rms;
      for (std::size_t k = 0; k < sweep.size(); ++k) {
        if (sweep[k].world == w && sweep[k].gain == gain) rms.push_back(rms_error_px[k]);
      }
      const double median = Median(rms);
      if (median < best) {
        best = median;
        best_gain[plan.worlds[w].name] = gain;
      }
    }
  }
  return best_gain;
}

}  // namespace kapfix::bench
