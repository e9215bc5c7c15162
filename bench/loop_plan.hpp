#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "common/evaluation/closed_loop_evaluation.hpp"
#include "common/sim/world_options.hpp"

namespace kapfix::bench {

// A world of the loop benchmark (issue 9): the nominal one, each field disturbance alone, or
// the realistic one with all of them.
struct LoopWorld {
  std::string name;
  WorldOptions options;
};

// The benchmark's twelve worlds, in table order.
std::vector<LoopWorld> LoopWorlds();

// One flight: a scene flown in a world by a controller from a start, with a seed.
struct LoopFlight {
  std::string scene;       // an opencv-doc photo, e.g. "left01.jpg"
  std::size_t world = 0;   // index into LoopPlan::worlds
  std::string controller;  // "predictive", "pid" or "p"
  std::string start;       // "first-frame" (--mode fixate), "ssp" (after SSP) or "moving"
  double gain = 1;         // P gain of "p" and "pid" (the predictive controller keeps its own)
  int seed = 1;

  // EvaluateClosedLoop's options for this flight in `world`, `frames` after the reference:
  // `agent_loop` (LoopPlan::agent_loop) with this flight's world, seed, start and controller.
  // P and PID take its gains with their own P gain (PID a little I and D), the predictive
  // controller its gains whole: each keeps the configured rate limit and dead band.
  ClosedLoopOptions Options(const ClosedLoopOptions& agent_loop, const WorldOptions& world,
                            int frames) const;
};

// What the benchmark flies: first P's gain sweep per world (seed 1, from the first frame, on
// the first sweep_scenes scenes), then every world × start × scene × seed × controller with
// P (and PID) at the world's best gain.
struct LoopPlan {
  int frames = 500;  // per flight, after the reference
  int seeds = 3;
  int sweep_scenes = 0;  // scenes the sweep flies per world (≤ scenes.size())
  std::vector<std::string> scenes;
  std::vector<LoopWorld> worlds;
  std::vector<std::string> controllers;  // "p" always among them: the baseline
  std::vector<std::string> starts;       // "first-frame", "ssp" and/or "moving"
  std::vector<double> sweep_gains;
  // The loop kapfix-agent --sim flies with its configuration (agent::MakeClosedLoopOptions):
  // servo speed, gains and their rate limit, search, frame period. Every flight starts from it.
  ClosedLoopOptions agent_loop;
  // Non-empty when the configuration's camera sees the simulated world at another scale than
  // the built-in's (agent::SimulatedWorldScaleNote): printed under the loop's line.
  std::string world_scale_note;

  bool IsValid(std::string* error) const;

  // The sweep's flights, per world, gain and scene (in that nesting).
  std::vector<LoopFlight> SweepFlights() const;
  // The main flights with P and PID at best_gain[world name], per world, start, scene, seed
  // and controller (the CSV's row order).
  std::vector<LoopFlight> MainFlights(const std::map<std::string, double>& best_gain) const;
  std::size_t SweepCount() const;
  std::size_t MainCount() const;
  // [s] wall-clock estimate of the whole plan at `jobs` parallel flights on `cores` cores,
  // from the cost per simulated frame measured on the project's machine (see the .cpp).
  double EstimatedSeconds(int jobs, int cores) const;
  // One line: the agent's loop every flight starts from (controller, gains, rate limit, frame
  // rate, servo speed, search), so that a table says what it measured.
  std::string DescribeAgentLoop() const;
  // The plan in a few lines (the agent's loop, flights per kind, the estimate), for --dry-run.
  std::string Describe(int jobs, int cores) const;
};

// P's best gain per world from the sweep: the gain with the lowest median RMS over the
// sweep's scenes (the first of equals). `sweep` and `rms_error_px` are index-aligned.
std::map<std::string, double> BestGains(const LoopPlan& plan, const std::vector<LoopFlight>& sweep,
                                        const std::vector<double>& rms_error_px);

}  // namespace kapfix::bench
