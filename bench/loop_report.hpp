#pragma once

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/loop_plan.hpp"
#include "bench/loop_run.hpp"

namespace kapfix::bench {

// The loop benchmark's figures from its flights: one row per world and start ("nominal" from
// the first frame, "nominal/ssp" after SSP), the predictive controller against P at the
// world's best gain and PID; the CSV (a line per flight), the printed tables, the heat map
// and summary.json. Everything is in the plan's order, whatever order the flights ran in.
class LoopReport {
 public:
  // `runs` are the plan's main flights (LoopPlan::MainFlights), any order.
  LoopReport(LoopPlan plan, std::map<std::string, double> best_gain, std::vector<LoopRun> runs);

  // One line per flight, in the order of `runs`.
  void WriteCsv(const std::string& path) const;
  // The per-world table, the predictive RMS per scene and the gross / silent gross per scene.
  void PrintTables(std::FILE* out) const;
  // The predictive RMS per scene and row as a PNG heat map.
  void WriteHeatMap(const std::string& path) const;
  // summary.json: the keys for the realistic world (from the first frame when it was
  // flown, else after SSP), every row's figures, and the targets per start.
  nlohmann::json Summary(const std::string& start_mode) const;

 private:
  struct Row {
    std::string label, world, start;
  };
  // A row's medians over scenes (of each scene's mean over seeds) and the predictive
  // controller's figures over its flights.
  struct RowFigures {
    double pred = 0, late = 0, p = 0, pid = 0;  // [px] median RMS (late: second half)
    double worst_ratio = 0;                     // [1] worst predictive ÷ P over scenes
    std::string worst_scene;
    double p95 = 0, gross = 0;                       // [px], [%] medians over flights
    double worst_silent = 0;                         // [%] highest silent_gross_pct over flights
    double ratio = 0, ratio_min = 0, ratio_max = 0;  // [1] deg/px estimate ÷ truth
    double floor = 0;  // [px] median aim floor over flights (the world's, whatever the loop)
  };

  RowFigures Figures(const Row& row) const;
  nlohmann::json RowJson(const Row& row) const;
  nlohmann::json StartJson(const std::string& start) const;
  void PrintWorldTable(std::FILE* out) const;
  void PrintSceneTables(std::FILE* out) const;

  LoopPlan plan_;
  std::map<std::string, double> best_gain_;
  std::vector<LoopRun> runs_;
  std::vector<Row> rows_;
  using PerScene = std::map<std::string, std::vector<double>>;
  std::map<std::string, std::map<std::string, PerScene>> rms_;  // row → scene → controller
  // The predictive controller's, per row (and scene).
  std::map<std::string, PerScene> late_, gross_by_scene_, silent_by_scene_;
  std::map<std::string, std::vector<double>> p95_, gross_, silent_, ratio_, floor_;
};

}  // namespace kapfix::bench
