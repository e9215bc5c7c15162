#include "agent/pipeline/flight_report.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "common/analysis/statistics.hpp"
#include "common/io/atomic_file.hpp"
#include "common/plot/line_plot.hpp"

namespace kapfix::agent {
namespace {

// [px] a true view error beyond this is gross (issue 9).
constexpr double kGrossErrorPx = 10;

// The online calibration at the flight's end against the truth (issue 9).
void FillCalibrationEstimate(const std::vector<TelemetryRecord>& records,
                             std::optional<double> true_deg_per_px, FlightFigures* f) {
  const TelemetryRecord* last = nullptr;  // the last fixating frame
  for (const TelemetryRecord& r : records) {
    if (r.reference_frame) last = &r;
  }
  if (last == nullptr) {
    f->deg_per_px_estimate_missing = "no fixating frame";
    return;
  }
  if (!last->estimate) {
    f->deg_per_px_estimate_missing = "the controller keeps no online deg/px estimate";
    return;
  }
  f->deg_per_px_estimate_sigma = last->estimate->pan.relative_sigma;
  f->deg_per_px_estimate_trusted = last->estimate->pan.trusted && last->estimate->tilt.trusted;
  if (!true_deg_per_px || !(*true_deg_per_px > 0)) {
    f->deg_per_px_estimate_missing = "not simulated: the true deg/px is unknown";
    return;
  }
  f->deg_per_px_estimate_ratio = last->estimate->pan.deg_per_px / *true_deg_per_px;
  f->deg_per_px_estimate_ratio_tilt = last->estimate->tilt.deg_per_px / *true_deg_per_px;
}

}  // namespace

FlightFigures ComputeFlightFigures(const std::vector<TelemetryRecord>& records,
                                   const PipelineStats& stats,
                                   std::optional<double> true_deg_per_px) {
  FlightFigures f;
  f.frames = records.size();
  f.fps = stats.wall_s > 0 ? static_cast<double>(stats.processed) / stats.wall_s : 0.0;
  // The simulation's truth is each frame's view offset from frame 0's view; what fixation
  // holds is the view of its reference frame, so the error is the difference of the two. A
  // view resumed after a restart was taken in another run: its truth is the frame that found
  // it, moved by where it was found there (the resume's match, within the matcher's miss).
  std::map<std::uint64_t, cv::Point2d> truth;
  for (const TelemetryRecord& r : records) {
    if (r.view_offset_x_px && r.view_offset_y_px) {
      truth[r.index] = {*r.view_offset_x_px, *r.view_offset_y_px};
    }
  }
  std::vector<double> latency, errors;
  double sum_sq = 0;
  std::size_t with_truth = 0, fixating = 0, lost = 0, gross = 0, silent_gross = 0;
  std::size_t gross_lock_held = 0, off_target = 0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    const TelemetryRecord& r = records[i];
    latency.push_back(r.loop_latency_ms);
    if (!r.reference_frame || *r.reference_frame == r.index) continue;
    ++fixating;
    lost += r.lock_lost ? 1 : 0;
    off_target += r.off_target ? 1 : 0;
    const auto now = truth.find(r.index);
    const auto held = truth.find(*r.reference_frame);
    if (now == truth.end() || held == truth.end()) continue;
    const cv::Point2d error = now->second - (held->second + r.reference_seen_at);
    sum_sq += error.dot(error);
    ++with_truth;
    errors.push_back(std::hypot(error.x, error.y));
    if (errors.back() > kGrossErrorPx) {
      ++gross;
      silent_gross += r.off_target ? 0 : 1;
      gross_lock_held += r.lock_lost ? 0 : 1;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto share = [with_truth, nan](std::size_t count) {
    return with_truth > 0 ? 100.0 * static_cast<double>(count) / static_cast<double>(with_truth)
                          : nan;
  };
  f.p95_error_px = errors.empty() ? nan : Percentile(errors, 95.0);
  f.gross_pct = share(gross);
  f.silent_gross_pct = share(silent_gross);
  f.gross_lock_held_pct = share(gross_lock_held);
  f.off_target_pct =
      fixating > 0 ? 100.0 * static_cast<double>(off_target) / static_cast<double>(fixating) : 0.0;
  f.rms_error_px = with_truth > 0 ? std::sqrt(sum_sq / static_cast<double>(with_truth))
                                  : std::numeric_limits<double>::quiet_NaN();
  f.lock_lost_pct =
      fixating > 0 ? 100.0 * static_cast<double>(lost) / static_cast<double>(fixating) : 0.0;
  f.loop_latency_p50_ms = latency.empty() ? 0.0 : Percentile(latency, 50.0);
  f.loop_latency_p99_ms = latency.empty() ? 0.0 : Percentile(latency, 99.0);
  f.rss_mb = PeakRssMb();
  FillCalibrationEstimate(records, true_deg_per_px, &f);
  return f;
}

PhotoFigures ComputePhotoFigures(const std::vector<kapfix::v1::PhotoMetadata>& photos) {
  PhotoFigures f;
  f.photos = photos.size();
  if (photos.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    f.view_speed_px_mean = f.view_blur_px_mean = f.offset_px_mean = f.sharpness_mean =
        f.wait_s_mean = f.lock_lost_share = nan;
    return f;
  }
  for (const auto& p : photos) {
    f.view_speed_px_mean += p.view_speed_px_per_frame();
    f.view_blur_px_mean += p.view_blur_px();
    f.offset_px_mean += p.residual_offset_px();
    f.sharpness_mean += p.sharpness_frame();
    f.wait_s_mean += p.shutter_wait_s();
    f.lock_lost_share += p.lock_lost() ? 1.0 : 0.0;
  }
  const auto n = static_cast<double>(photos.size());
  f.view_speed_px_mean /= n;
  f.view_blur_px_mean /= n;
  f.offset_px_mean /= n;
  f.sharpness_mean /= n;
  f.wait_s_mean /= n;
  f.lock_lost_share /= n;
  return f;
}

nlohmann::json FlightSummary(const FlightFigures& figures, const PhotoFigures& photos,
                             const PipelineStats& stats, const FlightDescription& flight) {
  const auto number = [](double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  };
  nlohmann::json summary = {
      {"rms_error_px", number(figures.rms_error_px)},
      {"lock_lost_pct", figures.lock_lost_pct},
      {"frames", figures.frames},
      {"fps", figures.fps},
      {"loop_latency_p50_ms", figures.loop_latency_p50_ms},
      {"loop_latency_p99_ms", figures.loop_latency_p99_ms},
      {"rss_mb", figures.rss_mb},
      {"controller", flight.controller},
      {"p95_error_px", number(figures.p95_error_px)},
      {"gross_pct", number(figures.gross_pct)},
      {"silent_gross_pct", number(figures.silent_gross_pct)},
      {"gross_lock_held_pct", number(figures.gross_lock_held_pct)},
      {"off_target_pct", figures.off_target_pct},
      // The online calibration's final estimate ÷ the simulated truth (issue 9); null with
      // the reason in deg_per_px_estimate_missing.
      {"deg_per_px_estimate_ratio", number(figures.deg_per_px_estimate_ratio)},
      {"deg_per_px_estimate_ratio_tilt", number(figures.deg_per_px_estimate_ratio_tilt)},
      {"deg_per_px_estimate_sigma", number(figures.deg_per_px_estimate_sigma)},
      {"deg_per_px_estimate_trusted", figures.deg_per_px_estimate_trusted},
      {"world", flight.simulated ? flight.world : std::string("none")},
      {"scene", flight.simulated ? flight.scene : std::string()},
      {"motion", flight.simulated ? flight.motion : std::string("none")},
      {"simulated", flight.simulated},
      {"dropped_frames", stats.dropped},
      {"watchdog_stalls", stats.watchdog_stalls},
      {"servo_errors", stats.servo_errors},
      {"servo_outages", stats.servo_outages},
      {"camera_reconnects", stats.camera_reconnects},
      {"shutter", flight.shutter},
      {"photos", photos.photos},
      {"photo_view_speed_px_mean", number(photos.view_speed_px_mean)},
      {"photo_view_blur_px_mean", number(photos.view_blur_px_mean)},
      {"photo_offset_px_mean", number(photos.offset_px_mean)},
      {"photo_sharpness_mean", number(photos.sharpness_mean)},
      {"photo_wait_s_mean", number(photos.wait_s_mean)},
      {"photo_lock_lost_share", number(photos.lock_lost_share)},
  };
  if (!figures.deg_per_px_estimate_missing.empty()) {
    summary["deg_per_px_estimate_missing"] = figures.deg_per_px_estimate_missing;
  }
  return summary;
}

double PeakRssMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      try {
        return std::stod(line.substr(6)) / 1024.0;  // kB
      } catch (const std::exception&) {
        return 0.0;
      }
    }
  }
  return 0.0;
}

void WriteFlightReport(const std::string& dir, const nlohmann::json& summary,
                       const std::vector<TelemetryRecord>& records) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw std::runtime_error("cannot create report folder '" + dir +
                             "': " + (ec ? ec.message() : "not a folder"));
  }
  const std::filesystem::path out(dir);
  WriteFileAtomically(out / "telemetry.csv", TelemetryRecorder::ToCsv(records));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  plot::PlotSeries mx{"measured x", {}, cv::Scalar(200, 80, 20)};
  plot::PlotSeries my{"measured y", {}, cv::Scalar(20, 140, 20)};
  plot::PlotSeries vx{"true view x", {}, cv::Scalar(20, 20, 220)};
  plot::PlotSeries vy{"true view y", {}, cv::Scalar(180, 40, 180)};
  for (const TelemetryRecord& r : records) {
    mx.y.push_back(r.found ? r.displacement_x_px : nan);
    my.y.push_back(r.found ? r.displacement_y_px : nan);
    vx.y.push_back(r.view_offset_x_px.value_or(nan));
    vy.y.push_back(r.view_offset_y_px.value_or(nan));
  }
  std::vector<plot::PlotSeries> series = {mx, my};
  if (std::any_of(vx.y.begin(), vx.y.end(), [](double v) { return std::isfinite(v); })) {
    series.push_back(vx);
    series.push_back(vy);
  }
  const cv::Mat png = plot::RenderLinePlot("displacement [px]", "frame", "px", series, {1000, 420});
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", png, bytes)) {
    throw std::runtime_error("cannot encode '" + (out / "displacement.png").string() + "'");
  }
  WriteFileAtomically(out / "displacement.png", std::string(bytes.begin(), bytes.end()));
  WriteFileAtomically(out / "summary.json", summary.dump(2) + "\n");
}

}  // namespace kapfix::agent
