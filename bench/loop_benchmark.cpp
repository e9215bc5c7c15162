// kapfix-bench-loop: the closed loop in a world it was not built for (issue 9). Scenes
// (opencv-doc photos, the chessboard left01.jpg included) × worlds (nominal, each field
// disturbance alone, realistic) × controllers (P at its best gain found by a sweep per world,
// PID, predictive — the default) × seeds, flown headless by EvaluateClosedLoop from the first
// frame (--mode fixate) and/or after SSP (--start). Prints a table, writes DIR/loop.csv,
// DIR/loop_heatmap.png and DIR/summary.json. Progress on stderr.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "common/evaluation/closed_loop_evaluation.hpp"
#include "common/plot/heat_map.hpp"

namespace kapfix::bench {
namespace {

const std::vector<std::string> kPhotos = {
    "aero1.jpg",   "aero3.jpg",  "building.jpg",     "fruits.jpg", "baboon.jpg",
    "leuvenA.jpg", "left01.jpg", "starry_night.jpg", "home.jpg",   "board.jpg"};

struct World {
  std::string name;
  WorldOptions options;
};

std::vector<World> Worlds() {
  const WorldOptions realistic = WorldOptions::Realistic();
  std::vector<World> worlds;
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

// How fixation starts: "first-frame" (--mode fixate) or "ssp" (SSP's slice after its free
// swing).
ClosedLoopOptions::Start ParseStart(const std::string& name) {
  return name == "ssp" ? ClosedLoopOptions::Start::kAfterSsp
                       : ClosedLoopOptions::Start::kFirstFrame;
}

struct Run {
  std::string scene, world, controller, start;
  double gain = 1;
  int seed = 1;
  ClosedLoopFigures figures;
};

ClosedLoopOptions Options(const World& world, const std::string& controller, double gain, int seed,
                          int frames, const std::string& start) {
  ClosedLoopOptions o;
  o.frames = frames;
  o.start = ParseStart(start);
  o.world = world.options;
  o.controller = controller;
  if (controller != "predictive") o.gains.p = gain;  // the default controller keeps its gains
  if (controller == "pid") {
    // A PID as an operator would set it: the P gain plus a little integral and derivative.
    o.gains.i = 0.5;
    o.gains.d = 0.01;
  }
  o.platform.kite.seed = static_cast<std::uint32_t>(seed);
  o.platform.camera.seed = static_cast<std::uint32_t>(seed);
  return o;
}

// One line per frame of a flight: the true view error, the servos' true output angles, what
// the loop believed them to be and what it commanded after the frame, and the measured
// displacement against the true one (−view error) — to see where a world's error is made.
void WriteTrace(const std::string& path, const ClosedLoopFigures& f) {
  std::ofstream out(path);
  out << "frame,err_x,err_y,true_pan,true_tilt,believed_pan,believed_tilt,commanded_pan,"
         "commanded_tilt,measured_x,measured_y,lock_lost,off_target\n";
  for (std::size_t k = 0; k < f.view_offsets.size(); ++k) {
    out << k + 1 << ',' << f.view_offsets[k].x << ',' << f.view_offsets[k].y << ','
        << f.angles[k].pan_deg << ',' << f.angles[k].tilt_deg << ',' << f.believed[k].pan_deg << ','
        << f.believed[k].tilt_deg << ',' << f.commanded[k].pan_deg << ',' << f.commanded[k].tilt_deg
        << ',' << f.measured_x[k] << ',' << f.measured_y[k] << ',' << (f.lock_lost[k] ? 1 : 0)
        << ',' << (f.off_target[k] ? 1 : 0) << '\n';
  }
}

double Median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double Mean(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x;
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : s / static_cast<double>(v.size());
}

double Lowest(const std::vector<double>& v) {
  return v.empty() ? std::numeric_limits<double>::quiet_NaN()
                   : *std::min_element(v.begin(), v.end());
}

std::vector<double> Negated(std::vector<double> v) {
  for (double& x : v) x = -x;
  return v;
}

// Named exception to the function-size check: the benchmark's options and its table, one
// run from top to bottom.
// NOLINTNEXTLINE(readability-function-size,readability-function-cognitive-complexity)
int Main(int argc, char** argv) {
  CLI::App app{"kapfix-bench-loop: closed loop over scenes × worlds × controllers × seeds"};
  bool quick = false;
  int frames = 0, seeds = 3, sweep_scenes = 0;
  std::string out_dir = "loop-bench";
  std::vector<std::string> only_worlds, only_scenes, only_controllers;
  bool detail = false, trace = false;
  std::string start_mode = "first-frame";
  app.add_flag("--quick", quick, "fewer frames and a smaller P-gain sweep (a few minutes)");
  app.add_option("--frames", frames,
                 "frames per flight after the reference (default 500; quick 250)")
      ->check(CLI::Range(20, 100000));
  app.add_option("--seeds", seeds, "seeds per scene and world (≥ 3 for the issue's table)")
      ->check(CLI::Range(1, 100));
  app.add_option("--sweep-scenes", sweep_scenes,
                 "scenes the P-gain sweep flies per world (default all; quick 3)")
      ->check(CLI::Range(1, 100));
  app.add_option("--worlds", only_worlds,
                 "only these worlds (default all), e.g. nominal realistic");
  app.add_option("--scenes", only_scenes, "only these photos (default all ten), e.g. aero1.jpg");
  app.add_option("--controllers", only_controllers,
                 "only these controllers (default predictive pid p); P's sweep always runs");
  app.add_flag("--detail", detail,
               "one line per flight on stderr: x/y RMS, the matcher's miss, forecast share");
  app.add_flag("--trace", trace,
               "per flight, DIR/trace_WORLD_SCENE_CONTROLLER_GAIN_SEED.csv: one line per frame "
               "(view error, true/believed/commanded servo angles, measured displacement)");
  app.add_option("--start", start_mode,
                 "how fixation starts: first-frame (--mode fixate), ssp (after SSP's 300-frame "
                 "free swing, on its slice) or both")
      ->check(CLI::IsMember({"first-frame", "ssp", "both"}));
  app.add_option("--out", out_dir, "folder for loop.csv, loop_heatmap.png, summary.json");
  CLI11_PARSE(app, argc, argv);
  const std::vector<std::string> starts = start_mode == "both"
                                              ? std::vector<std::string>{"first-frame", "ssp"}
                                              : std::vector<std::string>{start_mode};
  if (frames == 0) frames = quick ? 200 : 500;
  std::vector<std::string> photos = kPhotos;
  if (!only_scenes.empty()) photos = only_scenes;
  std::vector<std::string> controllers = {"predictive", "pid", "p"};
  if (!only_controllers.empty()) {
    controllers = only_controllers;
    // P at its best gain is the baseline every figure is compared with.
    if (std::find(controllers.begin(), controllers.end(), "p") == controllers.end()) {
      controllers.emplace_back("p");
    }
  }
  if (sweep_scenes == 0) sweep_scenes = quick ? 2 : static_cast<int>(photos.size());
  sweep_scenes = std::min(sweep_scenes, static_cast<int>(photos.size()));
  const std::vector<double> sweep_gains =
      quick ? std::vector<double>{0.5, 0.75, 1.0} : std::vector<double>{0.4, 0.6, 0.8, 1.0, 1.2};

  std::map<std::string, cv::Mat> scenes;
  for (const std::string& name : photos) {
    const std::string path = std::string(KAPFIX_OPENCV_DATA_DIR) + "/" + name;
    cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty()) {
      std::fprintf(stderr, "kapfix-bench-loop: cannot read %s (package opencv-doc)\n",
                   path.c_str());
      return 1;
    }
    scenes[name] = image;
  }
  std::filesystem::create_directories(out_dir);
  std::vector<World> worlds = Worlds();
  if (!only_worlds.empty()) {
    std::erase_if(worlds, [&only_worlds](const World& w) {
      return std::find(only_worlds.begin(), only_worlds.end(), w.name) == only_worlds.end();
    });
    if (worlds.size() != only_worlds.size()) {
      std::fprintf(stderr, "kapfix-bench-loop: unknown world in --worlds (known:");
      for (const World& w : Worlds()) std::fprintf(stderr, " %s", w.name.c_str());
      std::fprintf(stderr, ")\n");
      return 2;
    }
  }
  const std::size_t total =
      worlds.size() *
      (sweep_gains.size() * static_cast<std::size_t>(sweep_scenes) +
       starts.size() * controllers.size() * photos.size() * static_cast<std::size_t>(seeds));
  std::size_t done = 0;
  const auto fly = [&](const std::string& scene, const World& world, const std::string& controller,
                       double gain, int seed, const std::string& start) {
    Run run{
        scene,
        world.name,
        controller,
        start,
        gain,
        seed,
        EvaluateClosedLoop(scenes[scene], Options(world, controller, gain, seed, frames, start))};
    ++done;
    std::fprintf(stderr, "\r[%zu/%zu] %-9s %-16s %-10s %-11s %4.2f seed %d: %6.2f px   ", done,
                 total, world.name.c_str(), scene.c_str(), controller.c_str(), start.c_str(), gain,
                 seed, run.figures.rms_error_px);
    if (trace) {
      char gain_text[16];
      std::snprintf(gain_text, sizeof gain_text, "%.2f", gain);
      WriteTrace(out_dir + "/trace_" + world.name + "_" + scene + "_" + controller + "_" + start +
                     "_" + gain_text + "_" + std::to_string(seed) + ".csv",
                 run.figures);
    }
    if (detail) {
      const ClosedLoopFigures& f = run.figures;
      double late = 0;  // [px] RMS over the flight's second half (after the lock-on)
      const std::size_t half = f.view_offsets.size() / 2;
      for (std::size_t k = half; k < f.view_offsets.size(); ++k) {
        late += f.view_offsets[k].dot(f.view_offsets[k]);
      }
      late = std::sqrt(late / static_cast<double>(std::max<std::size_t>(1, half)));
      std::fprintf(stderr,
                   "late %6.2f | x %6.2f y %6.2f | miss %5.2f | forecast %5.1f%% lost %5.1f%% | "
                   "open %6.2f | deg/px ratio %5.3f σ %5.3f%s\n",
                   late, f.rms_error_x_px, f.rms_error_y_px, f.measurement_rms_px, f.predicting_pct,
                   f.lock_lost_pct, f.open_loop_rms_px, f.deg_per_px_estimate_ratio,
                   f.deg_per_px_estimate_sigma, f.deg_per_px_estimate_trusted ? " trusted" : "");
    }
    return run;
  };

  std::vector<Run> runs;
  std::map<std::string, double> best_gain;
  for (const World& world : worlds) {
    // P's best gain in this world: the lowest median RMS over the sweep's scenes (seed 1).
    double best = std::numeric_limits<double>::infinity();
    for (const double gain : sweep_gains) {
      std::vector<double> rms;
      for (int s = 0; s < sweep_scenes; ++s) {
        rms.push_back(fly(photos[static_cast<std::size_t>(s)], world, "p", gain, 1, "first-frame")
                          .figures.rms_error_px);
      }
      if (Median(rms) < best) {
        best = Median(rms);
        best_gain[world.name] = gain;
      }
    }
    for (const std::string& start : starts) {
      for (const std::string& scene : photos) {
        for (int seed = 1; seed <= seeds; ++seed) {
          // P at its best gain is what the others are compared with (issue 9); PID starts
          // from the same gain.
          for (const std::string& controller : controllers) {
            runs.push_back(fly(scene, world, controller, best_gain[world.name], seed, start));
          }
        }
      }
    }
  }
  std::fprintf(stderr, "\n");

  // CSV, one row per flight.
  {
    std::ofstream csv(out_dir + "/loop.csv");
    csv << "scene,world,start,slice,controller,p_gain,seed,rms_error_px,p95_error_px,gross_pct,"
           "silent_gross_pct,lock_lost_pct,dropped_pct,gross_lock_held_pct,off_target_pct\n";
    for (const Run& r : runs) {
      const ClosedLoopFigures& f = r.figures;
      csv << r.scene << ',' << r.world << ',' << r.start << ',' << f.slice << ',' << r.controller
          << ',' << r.gain << ',' << r.seed << ',' << f.rms_error_px << ',' << f.p95_error_px << ','
          << f.gross_pct << ',' << f.silent_gross_pct << ',' << f.lock_lost_pct << ','
          << f.dropped_pct << ',' << f.gross_lock_held_pct << ',' << f.off_target_pct << '\n';
    }
  }

  // One table row per world and start: "nominal" from the first frame, "nominal/ssp" after SSP.
  struct Row {
    std::string label, world;
  };
  const auto label_of = [](const std::string& world, const std::string& start) {
    return start == "ssp" ? world + "/ssp" : world;
  };
  std::vector<Row> rows;
  for (const World& world : worlds) {
    for (const std::string& start : starts)
      rows.push_back({label_of(world.name, start), world.name});
  }
  // Per scene and row: the mean over seeds of each controller's RMS.
  std::map<std::string, std::map<std::string, std::map<std::string, std::vector<double>>>> rms;
  std::map<std::string, std::map<std::string, std::vector<double>>> gross_by_scene, silent_by_scene;
  std::map<std::string, double> worst_silent;  // per row, over scenes and seeds
  std::map<std::string, std::vector<double>> p95_by_world, gross_by_world, ratio_by_world;
  for (const Run& r : runs) {
    const std::string row = label_of(r.world, r.start);
    rms[row][r.scene][r.controller].push_back(r.figures.rms_error_px);
    if (r.controller == "predictive") {
      worst_silent[row] = std::max(worst_silent[row], r.figures.silent_gross_pct);
      p95_by_world[row].push_back(r.figures.p95_error_px);
      gross_by_world[row].push_back(r.figures.gross_pct);
      gross_by_scene[row][r.scene].push_back(r.figures.gross_pct);
      silent_by_scene[row][r.scene].push_back(r.figures.silent_gross_pct);
      ratio_by_world[row].push_back(r.figures.deg_per_px_estimate_ratio);
    }
  }
  std::printf("%d frames, %d seeds, P gain swept over", frames, seeds);
  for (const double g : sweep_gains) std::printf(" %.2f", g);
  std::printf(" on %d scenes\n\n", sweep_scenes);
  std::printf("%-14s %7s | %9s %9s %9s | %12s %11s | %10s %8s | %9s\n", "world", "P gain",
              "pred_px", "P*_px", "pid_px", "worst pred/P", "(scene)", "max silent", "gross%",
              "deg/px ×");
  std::vector<double> heat;
  nlohmann::json per_world = nlohmann::json::object();
  for (const Row& row : rows) {
    std::vector<double> pred, p, pid;
    double worst = 0;
    std::string worst_scene;
    for (const std::string& scene : photos) {
      auto& c = rms[row.label][scene];
      pred.push_back(Mean(c["predictive"]));
      p.push_back(Mean(c["p"]));
      pid.push_back(Mean(c["pid"]));
      const double ratio = pred.back() / p.back();
      if (ratio > worst) {
        worst = ratio;
        worst_scene = scene;
      }
    }
    std::printf("%-14s %7.2f | %9.2f %9.2f %9.2f | %12.2f %11s | %10.2f %8.2f | %9.3f\n",
                row.label.c_str(), best_gain[row.world], Median(pred), Median(p), Median(pid),
                worst, worst_scene.c_str(), worst_silent[row.label],
                Median(gross_by_world[row.label]), Median(ratio_by_world[row.label]));
    per_world[row.label] = {
        {"p_best_gain", best_gain[row.world]},
        {"median_rms_error_px", Median(pred)},
        {"median_rms_error_px_p_best", Median(p)},
        {"median_rms_error_px_pid", Median(pid)},
        {"worst_ratio_to_p_best", worst},
        {"worst_ratio_scene", worst_scene},
        {"p95_error_px", Median(p95_by_world[row.label])},
        {"gross_pct", Median(gross_by_world[row.label])},
        {"silent_gross_pct", worst_silent[row.label]},
        {"deg_per_px_estimate_ratio", Median(ratio_by_world[row.label])},
        {"deg_per_px_estimate_ratio_min", Lowest(ratio_by_world[row.label])},
        {"deg_per_px_estimate_ratio_max", -Lowest(Negated(ratio_by_world[row.label]))}};
  }
  std::printf("\npredictive RMS [px] per scene (mean over seeds):\n%-17s", "scene");
  for (const Row& row : rows) std::printf(" %14s", row.label.c_str());
  std::printf("\n");
  std::vector<std::string> world_names;
  for (const Row& row : rows) world_names.push_back(row.label);
  for (const std::string& scene : photos) {
    std::printf("%-17s", scene.c_str());
    for (const Row& row : rows) {
      const double v = Mean(rms[row.label][scene]["predictive"]);
      heat.push_back(v);
      std::printf(" %14.2f", v);
    }
    std::printf("\n");
  }
  // The lock's honesty per scene (issue 9): gross_pct / silent_gross_pct of the predictive
  // controller, mean over seeds.
  std::printf("\npredictive gross%% / silent gross%% per scene (mean over seeds):\n%-17s", "scene");
  for (const Row& row : rows) std::printf(" %14s", row.label.c_str());
  std::printf("\n");
  for (const std::string& scene : photos) {
    std::printf("%-17s", scene.c_str());
    for (const Row& row : rows) {
      std::printf("  %5.1f / %5.2f", Mean(gross_by_scene[row.label][scene]),
                  Mean(silent_by_scene[row.label][scene]));
    }
    std::printf("\n");
  }
  cv::imwrite(out_dir + "/loop_heatmap.png",
              plot::RenderHeatMap("predictive controller: RMS view error [px], mean over seeds",
                                  photos, world_names, heat, 1.0, 100.0));
  // The keys, for the realistic world (the default controller); the online
  // calibration's ratio is the median over its flights of the final estimate ÷ the truth.
  // (From the first frame when it was flown, else after SSP.)
  const std::string realistic_row = per_world.contains("realistic") ? "realistic" : "realistic/ssp";
  const nlohmann::json realistic =
      per_world.contains(realistic_row) ? per_world[realistic_row] : nlohmann::json::object();
  nlohmann::json summary = {
      {"frames", frames},
      {"seeds", seeds},
      {"p95_error_px", realistic.value("p95_error_px", nlohmann::json())},
      {"gross_pct", realistic.value("gross_pct", nlohmann::json())},
      {"silent_gross_pct", realistic.value("silent_gross_pct", nlohmann::json())},
      {"deg_per_px_estimate_ratio", realistic.value("deg_per_px_estimate_ratio", nlohmann::json())},
      {"start", start_mode},
      {"worlds", per_world}};
  std::ofstream(out_dir + "/summary.json") << summary.dump(2) << '\n';
  std::printf("\nwrote %s/loop.csv, %s/loop_heatmap.png, %s/summary.json\n", out_dir.c_str(),
              out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace
}  // namespace kapfix::bench

int main(int argc, char** argv) {
  try {
    return kapfix::bench::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kapfix-bench-loop: %s\n", e.what());
    return 1;
  }
}
