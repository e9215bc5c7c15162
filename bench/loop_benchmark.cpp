// kapfix-bench-loop: the closed loop in a world it was not built for (issue 9). Scenes
// (opencv-doc photos, the chessboard left01.jpg included) × worlds (nominal, each field
// disturbance alone, realistic) × controllers (P at its best gain found by a sweep per world,
// PID, predictive — the default) × seeds, flown headless by EvaluateClosedLoop from the first
// frame (--mode fixate) and/or after SSP (--start), --jobs flights at a time. Prints a table,
// writes DIR/loop.csv, DIR/loop_heatmap.png and DIR/summary.json, the same whatever --jobs.
// Progress on stderr. Every flight is the loop kapfix-agent --sim flies with its built-in
// configuration, or with --config's (servo speed, gains and their rate limit, search, frame
// rate), in the benchmark's own worlds and scenes.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <thread>
#include <vector>

#include "agent/agent.hpp"
#include "agent/config_file/agent_config_file.hpp"
#include "agent/modes/run_options.hpp"
#include "bench/loop_parallel_flights.hpp"
#include "bench/loop_plan.hpp"
#include "bench/loop_report.hpp"
#include "bench/loop_run.hpp"

namespace kapfix::bench {
namespace {

const std::vector<std::string> kPhotos = {
    "aero1.jpg",   "aero3.jpg",  "building.jpg",     "fruits.jpg", "baboon.jpg",
    "leuvenA.jpg", "left01.jpg", "starry_night.jpg", "home.jpg",   "board.jpg"};

int Cores() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

// The command line as given, before it becomes a plan.
struct LoopCommandLine {
  bool quick = false, detail = false, trace = false, dry_run = false;
  int frames = 0, seeds = 3, sweep_scenes = 0, jobs = Cores();
  std::string out_dir = "loop-bench";
  std::string config_path;
  std::string start_mode = "first-frame";
  std::vector<std::string> only_worlds, only_scenes, only_controllers;
};

void AddOptions(CLI::App& app, LoopCommandLine* c) {
  app.add_flag("--quick", c->quick, "fewer frames and a smaller P-gain sweep (a few minutes)");
  app.add_option("--frames", c->frames,
                 "frames per flight after the reference (default 500; quick 200)")
      ->check(CLI::Range(20, 100000));
  app.add_option("--seeds", c->seeds, "seeds per scene and world (≥ 3 for the issue's table)")
      ->check(CLI::Range(1, 100));
  app.add_option("--sweep-scenes", c->sweep_scenes,
                 "scenes the P-gain sweep flies per world (default all; quick 2)")
      ->check(CLI::Range(1, 100));
  app.add_option("--worlds", c->only_worlds,
                 "only these worlds (default all), e.g. nominal realistic");
  app.add_option("--scenes", c->only_scenes, "only these photos (default all ten), e.g. aero1.jpg");
  app.add_option("--controllers", c->only_controllers,
                 "only these controllers (default predictive pid p); P's sweep always runs");
  app.add_flag("--detail", c->detail,
               "one line per flight on stderr: x/y RMS, the matcher's miss, forecast share");
  app.add_flag("--trace", c->trace,
               "per flight, DIR/trace_WORLD_SCENE_CONTROLLER_START_GAIN_SEED.csv: one line per "
               "frame (view error, true/believed/commanded servo angles, measured displacement and "
               "its confidence, lock)");
  app.add_option("--start", c->start_mode,
                 "how fixation starts: first-frame (--mode fixate), ssp (after SSP's 300-frame "
                 "free swing, on its slice), both (those two: the issue's), or moving (a frame "
                 "into the swing: the reference carries the swing's motion blur)")
      ->check(CLI::IsMember({"first-frame", "ssp", "both", "moving"}));
  app.add_option("--jobs", c->jobs, "flights at a time (default: the machine's cores)")
      ->check(CLI::Range(1, 256));
  app.add_flag("--dry-run", c->dry_run,
               "print the plan (flights per kind, the time estimate) and fly nothing");
  app.add_option("--out", c->out_dir, "folder for loop.csv, loop_heatmap.png, summary.json");
  app.add_option("--config", c->config_path,
                 "fly the loop of this kapfix-agent configuration file (servos, gains, search, "
                 "camera rate; its scene and world are the benchmark's); default: the agent's "
                 "built-in simulation")
      ->check(CLI::ExistingFile);
}

// The worlds named in `only` (all when empty), in table order; false and a one-line reason
// for an unknown name.
bool SelectWorlds(const std::vector<std::string>& only, std::vector<LoopWorld>* worlds,
                  std::string* error) {
  *worlds = LoopWorlds();
  if (only.empty()) return true;
  std::erase_if(*worlds, [&only](const LoopWorld& w) {
    return std::find(only.begin(), only.end(), w.name) == only.end();
  });
  if (worlds->size() == only.size()) return true;
  *error = "unknown world in --worlds (known:";
  for (const LoopWorld& w : LoopWorlds()) *error += " " + w.name;
  *error += ")";
  return false;
}

// The loop kapfix-agent flies: with --config's configuration, else its built-in one (a kite);
// false and the configuration's error.
bool ReadAgentLoop(const std::string& config_path, LoopPlan* plan, std::string* error) {
  agent::AgentConfig config = agent::BuiltInConfig(agent::MotionKind::kKite);
  if (!config_path.empty()) {
    if (!agent::LoadAgentConfig(config_path, &config, error) || !config.IsValid(error)) {
      return false;
    }
  }
  plan->agent_loop = agent::MakeClosedLoopOptions(config);
  plan->world_scale_note = agent::SimulatedWorldScaleNote(config).value_or("");
  return true;
}

LoopPlan MakePlan(const LoopCommandLine& c) {
  LoopPlan plan;
  plan.frames = c.frames != 0 ? c.frames : (c.quick ? 200 : 500);
  plan.seeds = c.seeds;
  plan.scenes = c.only_scenes.empty() ? kPhotos : c.only_scenes;
  plan.controllers = {"predictive", "pid", "p"};
  if (!c.only_controllers.empty()) {
    plan.controllers = c.only_controllers;
    // P at its best gain is the baseline every figure is compared with.
    if (std::find(plan.controllers.begin(), plan.controllers.end(), "p") ==
        plan.controllers.end()) {
      plan.controllers.emplace_back("p");
    }
  }
  plan.starts = c.start_mode == "both" ? std::vector<std::string>{"first-frame", "ssp"}
                                       : std::vector<std::string>{c.start_mode};
  const int scene_count = static_cast<int>(plan.scenes.size());
  plan.sweep_scenes =
      std::min(c.sweep_scenes != 0 ? c.sweep_scenes : (c.quick ? 2 : scene_count), scene_count);
  plan.sweep_gains = c.quick ? std::vector<double>{0.5, 0.75, 1.0}
                             : std::vector<double>{0.4, 0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0};
  return plan;
}

// The plan's photos from the opencv-doc folder; false and a reason for one that cannot be
// read.
bool ReadScenes(const LoopPlan& plan, std::map<std::string, cv::Mat>* scenes, std::string* error) {
  for (const std::string& name : plan.scenes) {
    const std::string path = std::string(KAPFIX_OPENCV_DATA_DIR) + "/" + name;
    cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty()) {
      *error = "cannot read " + path + " (package opencv-doc)";
      return false;
    }
    (*scenes)[name] = image;
  }
  return true;
}

// "[k/N] …" on stderr as flights finish (called one at a time by FlyInParallel).
struct Progress {
  std::size_t done = 0, total = 0;
  bool detail = false;

  void Report(const LoopRun& run) {
    std::fprintf(stderr, "%s", run.ProgressLine(++done, total).c_str());
    if (detail) std::fprintf(stderr, "%s", run.DetailLine().c_str());
  }
};

// Flies `flights` `jobs` at a time; the runs in the order of `flights`.
std::vector<LoopRun> FlyAll(const std::vector<LoopFlight>& flights, const LoopPlan& plan,
                            const std::map<std::string, cv::Mat>& scenes, int jobs,
                            const std::string& trace_dir, Progress* progress) {
  std::vector<LoopRun> runs(flights.size());
  FlyInParallel(
      flights.size(), jobs,
      [&](std::size_t k) {
        const LoopFlight& flight = flights[k];
        runs[k] = Fly(scenes.at(flight.scene), flight, plan.agent_loop, plan.worlds[flight.world],
                      plan.frames, trace_dir);
      },
      [&](std::size_t k) { progress->Report(runs[k]); });
  return runs;
}

// Flies each world briefly (2 frames, after a 10-frame SSP when the plan has it) on this
// thread, results dropped, before any worker starts: OpenCV fills some tables on first use
// without a lock (cv::RNG's normal-distribution tables; helgrind saw two workers write them),
// so they are filled here once.
void WarmUp(const LoopPlan& plan, const cv::Mat& scene) {
  for (const LoopWorld& world : plan.worlds) {
    for (const std::string& start : plan.starts) {
      ClosedLoopOptions options =
          LoopFlight{"", 0, "predictive", start, 1.0, 1}.Options(plan.agent_loop, world.options, 2);
      options.ssp_frames = 10;  // ≥ 2 reach the camera: the worlds drop at most 2 %
      EvaluateClosedLoop(scene, options);
    }
  }
}

// P's gain sweep per world, then every main flight with the world's best gain; the report.
LoopReport FlyPlan(const LoopPlan& plan, const LoopCommandLine& c,
                   const std::map<std::string, cv::Mat>& scenes) {
  const std::string trace_dir = c.trace ? c.out_dir : "";
  Progress progress{0, plan.SweepCount() + plan.MainCount(), c.detail};
  const std::vector<LoopFlight> sweep = plan.SweepFlights();
  std::vector<double> sweep_rms;
  std::map<std::string, double> best_gain;
  std::vector<LoopRun> runs;
  try {
    for (const LoopRun& run : FlyAll(sweep, plan, scenes, c.jobs, trace_dir, &progress)) {
      sweep_rms.push_back(run.figures.rms_error_px);
    }
    best_gain = BestGains(plan, sweep, sweep_rms);
    runs = FlyAll(plan.MainFlights(best_gain), plan, scenes, c.jobs, trace_dir, &progress);
  } catch (...) {
    std::fprintf(stderr, "\n");  // the error's line after the progress line, not on it
    throw;
  }
  std::fprintf(stderr, "\n");
  return LoopReport(plan, std::move(best_gain), std::move(runs));
}

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-bench-loop: closed loop over scenes × worlds × controllers × seeds"};
  LoopCommandLine c;
  AddOptions(app, &c);
  CLI11_PARSE(app, argc, argv);
  LoopPlan plan = MakePlan(c);
  std::string error;
  if (!SelectWorlds(c.only_worlds, &plan.worlds, &error) ||
      !ReadAgentLoop(c.config_path, &plan, &error) || !plan.IsValid(&error)) {
    std::fprintf(stderr, "kapfix-bench-loop: %s\n", error.c_str());
    return 2;
  }
  if (c.dry_run) {
    std::printf("%s", plan.Describe(c.jobs, Cores()).c_str());
    return 0;
  }
  std::map<std::string, cv::Mat> scenes;
  if (!ReadScenes(plan, &scenes, &error)) {
    std::fprintf(stderr, "kapfix-bench-loop: %s\n", error.c_str());
    return 1;
  }
  std::fprintf(stderr, "%s", plan.DescribeAgentLoop().c_str());
  std::fprintf(stderr, "%zu flights, about %.0f min at --jobs %d\n",
               plan.SweepCount() + plan.MainCount(),
               std::max(1.0, plan.EstimatedSeconds(c.jobs, Cores()) / 60.0), c.jobs);
  // The flights are the parallelism: OpenCV's own threads inside each would only fight them.
  if (c.jobs > 1) {
    cv::setNumThreads(1);
    WarmUp(plan, scenes.at(plan.scenes.front()));
  }
  std::filesystem::create_directories(c.out_dir);
  const LoopReport report = FlyPlan(plan, c, scenes);
  report.WriteCsv(c.out_dir + "/loop.csv");
  report.PrintTables(stdout);
  report.WriteHeatMap(c.out_dir + "/loop_heatmap.png");
  std::ofstream(c.out_dir + "/summary.json") << report.Summary(c.start_mode).dump(2) << '\n';
  std::printf("\nwrote %s/loop.csv, %s/loop_heatmap.png, %s/summary.json\n", c.out_dir.c_str(),
              c.out_dir.c_str(), c.out_dir.c_str());
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
