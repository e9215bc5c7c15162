#include "bench/loop_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <utility>

#include "common/plot/heat_map.hpp"

namespace kapfix::bench {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// The order statistics here take what the flights gave, NaN included (a controller not
// flown), and give NaN for nothing rather than throwing: a narrowed run still prints.
double Median(std::vector<double> v) {
  if (v.empty()) return kNan;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double Mean(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x;
  return v.empty() ? kNan : s / static_cast<double>(v.size());
}

double Lowest(const std::vector<double>& v) {
  return v.empty() ? kNan : *std::min_element(v.begin(), v.end());
}

double Highest(const std::vector<double>& v) {
  return v.empty() ? kNan : *std::max_element(v.begin(), v.end());
}

// The table's row label: "nominal" from the first frame, "nominal/ssp" after SSP,
// "nominal/moving" from a frame into the swing.
std::string Label(const std::string& world, const std::string& start) {
  return start == "first-frame" ? world : world + "/" + start;
}

// A list in the plan, or an empty one when `key` has none.
template <typename Map>
const typename Map::mapped_type& Find(const Map& map, const std::string& key) {
  static const typename Map::mapped_type kNone{};
  const auto it = map.find(key);
  return it == map.end() ? kNone : it->second;
}

}  // namespace

LoopReport::LoopReport(LoopPlan plan, std::map<std::string, double> best_gain,
                       std::vector<LoopRun> runs)
    : plan_(std::move(plan)), best_gain_(std::move(best_gain)), runs_(std::move(runs)) {
  for (const LoopWorld& world : plan_.worlds) {
    for (const std::string& start : plan_.starts) {
      rows_.push_back({Label(world.name, start), world.name, start});
    }
  }
  for (const LoopRun& r : runs_) {
    const std::string row = Label(r.world, r.flight.start);
    const ClosedLoopFigures& f = r.figures;
    rms_[row][r.flight.scene][r.flight.controller].push_back(f.rms_error_px);
    if (r.flight.controller != "predictive") continue;
    late_[row][r.flight.scene].push_back(r.late_rms_error_px);
    silent_[row].push_back(f.silent_gross_pct);
    p95_[row].push_back(f.p95_error_px);
    gross_[row].push_back(f.gross_pct);
    gross_by_scene_[row][r.flight.scene].push_back(f.gross_pct);
    silent_by_scene_[row][r.flight.scene].push_back(f.silent_gross_pct);
    ratio_[row].push_back(f.deg_per_px_estimate_ratio);
    floor_[row].push_back(f.aim_floor_rms_px);
  }
}

LoopReport::RowFigures LoopReport::Figures(const Row& row) const {
  RowFigures figures;
  std::vector<double> pred, late, p, pid;
  const auto& rms = Find(rms_, row.label);
  const auto& late_by_scene = Find(late_, row.label);
  for (const std::string& scene : plan_.scenes) {
    const PerScene& c = Find(rms, scene);
    pred.push_back(Mean(Find(c, "predictive")));
    late.push_back(Mean(Find(late_by_scene, scene)));
    p.push_back(Mean(Find(c, "p")));
    pid.push_back(Mean(Find(c, "pid")));
    const double ratio = pred.back() / p.back();
    if (ratio > figures.worst_ratio) {
      figures.worst_ratio = ratio;
      figures.worst_scene = scene;
    }
  }
  figures.pred = Median(pred);
  figures.late = Median(late);
  figures.p = Median(p);
  figures.pid = Median(pid);
  figures.p95 = Median(Find(p95_, row.label));
  figures.gross = Median(Find(gross_, row.label));
  const std::vector<double>& silent = Find(silent_, row.label);
  figures.worst_silent = silent.empty() ? 0.0 : Highest(silent);
  const std::vector<double>& ratio = Find(ratio_, row.label);
  figures.ratio = Median(ratio);
  figures.ratio_min = Lowest(ratio);
  figures.ratio_max = Highest(ratio);
  figures.floor = Median(Find(floor_, row.label));
  return figures;
}

void LoopReport::WriteCsv(const std::string& path) const {
  std::ofstream csv(path);
  csv << "scene,world,start,slice,controller,p_gain,seed,rms_error_px,p95_error_px,gross_pct,"
         "silent_gross_pct,lock_lost_pct,dropped_pct,gross_lock_held_pct,off_target_pct\n";
  for (const LoopRun& r : runs_) {
    const ClosedLoopFigures& f = r.figures;
    csv << r.flight.scene << ',' << r.world << ',' << r.flight.start << ',' << f.slice << ','
        << r.flight.controller << ',' << r.flight.gain << ',' << r.flight.seed << ','
        << f.rms_error_px << ',' << f.p95_error_px << ',' << f.gross_pct << ','
        << f.silent_gross_pct << ',' << f.lock_lost_pct << ',' << f.dropped_pct << ','
        << f.gross_lock_held_pct << ',' << f.off_target_pct << '\n';
  }
  if (!csv) throw std::runtime_error("cannot write " + path);
}

void LoopReport::PrintTables(std::FILE* out) const {
  std::fprintf(out, "%d frames, %d seeds, P gain swept over", plan_.frames, plan_.seeds);
  for (const double g : plan_.sweep_gains) std::fprintf(out, " %.2f", g);
  std::fprintf(out, " on %d scenes\n\n", plan_.sweep_scenes);
  PrintWorldTable(out);
  PrintSceneTables(out);
}

void LoopReport::PrintWorldTable(std::FILE* out) const {
  std::fprintf(out, "%-14s %7s | %9s %9s %9s %9s %9s | %12s %11s | %10s %8s | %9s\n", "world",
               "P gain", "pred_px", "late_px", "P*_px", "pid_px", "floor_px", "worst pred/P",
               "(scene)", "max silent", "gross%", "deg/px ×");
  for (const Row& row : rows_) {
    const RowFigures f = Figures(row);
    std::fprintf(
        out, "%-14s %7.2f | %9.2f %9.2f %9.2f %9.2f %9.2f | %12.2f %11s | %10.2f %8.2f | %9.3f\n",
        row.label.c_str(), best_gain_.at(row.world), f.pred, f.late, f.p, f.pid, f.floor,
        f.worst_ratio, f.worst_scene.c_str(), f.worst_silent, f.gross, f.ratio);
  }
}

void LoopReport::PrintSceneTables(std::FILE* out) const {
  const auto header = [&](const char* title) {
    std::fprintf(out, "\n%s\n%-17s", title, "scene");
    for (const Row& row : rows_) std::fprintf(out, " %14s", row.label.c_str());
    std::fprintf(out, "\n");
  };
  header("predictive RMS [px] per scene (mean over seeds):");
  for (const std::string& scene : plan_.scenes) {
    std::fprintf(out, "%-17s", scene.c_str());
    for (const Row& row : rows_) {
      std::fprintf(out, " %14.2f", Mean(Find(Find(Find(rms_, row.label), scene), "predictive")));
    }
    std::fprintf(out, "\n");
  }
  // The lock's honesty per scene (issue 9): gross_pct / silent_gross_pct of the predictive
  // controller, mean over seeds.
  header("predictive gross% / silent gross% per scene (mean over seeds):");
  for (const std::string& scene : plan_.scenes) {
    std::fprintf(out, "%-17s", scene.c_str());
    for (const Row& row : rows_) {
      std::fprintf(out, "  %5.1f / %5.2f", Mean(Find(Find(gross_by_scene_, row.label), scene)),
                   Mean(Find(Find(silent_by_scene_, row.label), scene)));
    }
    std::fprintf(out, "\n");
  }
}

void LoopReport::WriteHeatMap(const std::string& path) const {
  std::vector<double> heat;
  std::vector<std::string> labels;
  for (const Row& row : rows_) labels.push_back(row.label);
  for (const std::string& scene : plan_.scenes) {
    for (const Row& row : rows_) {
      heat.push_back(Mean(Find(Find(Find(rms_, row.label), scene), "predictive")));
    }
  }
  if (!cv::imwrite(
          path, plot::RenderHeatMap("predictive controller: RMS view error [px], mean over seeds",
                                    plan_.scenes, labels, heat, 1.0, 100.0))) {
    throw std::runtime_error("cannot write " + path);
  }
}

nlohmann::json LoopReport::RowJson(const Row& row) const {
  const RowFigures f = Figures(row);
  return {{"p_best_gain", best_gain_.at(row.world)},
          {"median_rms_error_px", f.pred},
          {"median_late_rms_error_px", f.late},
          {"median_aim_floor_px", f.floor},
          {"median_rms_error_px_p_best", f.p},
          {"median_rms_error_px_pid", f.pid},
          {"worst_ratio_to_p_best", f.worst_ratio},
          {"worst_ratio_scene", f.worst_scene},
          {"p95_error_px", f.p95},
          {"gross_pct", f.gross},
          {"silent_gross_pct", f.worst_silent},
          {"deg_per_px_estimate_ratio", f.ratio},
          {"deg_per_px_estimate_ratio_min", f.ratio_min},
          {"deg_per_px_estimate_ratio_max", f.ratio_max}};
}

// The targets from one start (it counts both): the nominal and realistic medians
// (whole flight and second half), the realistic world's worst predictive ÷ P, and the highest
// silent gross share over every world flown.
nlohmann::json LoopReport::StartJson(const std::string& start) const {
  nlohmann::json figures = nlohmann::json::object();
  double silent = 0;
  std::string silent_world;
  for (const Row& row : rows_) {
    if (row.start != start) continue;
    const RowFigures f = Figures(row);
    if (row.world == "nominal" || row.world == "realistic") {
      figures[row.world + "_median_rms_error_px"] = f.pred;
      figures[row.world + "_median_late_rms_error_px"] = f.late;
      figures[row.world + "_worst_ratio_to_p_best"] = f.worst_ratio;
    }
    if (silent_world.empty() || f.worst_silent > silent) {
      silent = f.worst_silent;
      silent_world = row.world;
    }
  }
  figures["max_silent_gross_pct"] = silent;
  figures["max_silent_gross_world"] = silent_world;
  return figures;
}

nlohmann::json LoopReport::Summary(const std::string& start_mode) const {
  nlohmann::json per_world = nlohmann::json::object();
  for (const Row& row : rows_) per_world[row.label] = RowJson(row);
  nlohmann::json by_start = nlohmann::json::object();
  for (const std::string& start : plan_.starts) by_start[start] = StartJson(start);
  // The keys, for the realistic world (the default controller); the online
  // calibration's ratio is the median over its flights of the final estimate ÷ the truth.
  // From the first frame where it was flown, else from the first start flown.
  const bool first_frame =
      std::find(plan_.starts.begin(), plan_.starts.end(), "first-frame") != plan_.starts.end();
  const std::string realistic_row = Label(
      "realistic", first_frame || plan_.starts.empty() ? "first-frame" : plan_.starts.front());
  const nlohmann::json realistic =
      per_world.contains(realistic_row) ? per_world[realistic_row] : nlohmann::json::object();
  return {
      {"frames", plan_.frames},
      {"seeds", plan_.seeds},
      {"p95_error_px", realistic.value("p95_error_px", nlohmann::json())},
      {"gross_pct", realistic.value("gross_pct", nlohmann::json())},
      {"silent_gross_pct", realistic.value("silent_gross_pct", nlohmann::json())},
      {"deg_per_px_estimate_ratio", realistic.value("deg_per_px_estimate_ratio", nlohmann::json())},
      {"start", start_mode},
      {"by_start", by_start},
      {"worlds", per_world}};
}

}  // namespace kapfix::bench
