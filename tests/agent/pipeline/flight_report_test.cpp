// The flight report: the photos' means and the summary that kapfix-agent --report prints and
// writes (scripts read its keys).
#include "agent/pipeline/flight_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace kapfix::agent {
namespace {

TEST(FlightReportTest, PhotoFiguresAreTheMeansOverThePhotos) {
  std::vector<kapfix::v1::PhotoMetadata> photos(2);
  photos[0].set_view_speed_px_per_frame(1.0F);
  photos[0].set_residual_offset_px(2.0F);
  photos[0].set_sharpness_frame(100.0F);
  photos[0].set_shutter_wait_s(0.5F);
  photos[1].set_view_speed_px_per_frame(3.0F);
  photos[1].set_residual_offset_px(4.0F);
  photos[1].set_sharpness_frame(300.0F);
  photos[1].set_shutter_wait_s(0.0F);
  photos[1].set_lock_lost(true);
  const PhotoFigures f = ComputePhotoFigures(photos);
  EXPECT_EQ(f.photos, 2u);
  EXPECT_DOUBLE_EQ(f.view_speed_px_mean, 2.0);
  EXPECT_DOUBLE_EQ(f.offset_px_mean, 3.0);
  EXPECT_DOUBLE_EQ(f.sharpness_mean, 200.0);
  EXPECT_DOUBLE_EQ(f.wait_s_mean, 0.25);
  EXPECT_DOUBLE_EQ(f.lock_lost_share, 0.5);
}

TEST(FlightReportTest, NoPhotosHaveNoPhotoMeans) {
  const PhotoFigures f = ComputePhotoFigures({});
  EXPECT_EQ(f.photos, 0u);
  EXPECT_TRUE(std::isnan(f.view_speed_px_mean));
}

FlightDescription SimulatedKiteFlight() {
  return {.controller = "predictive",
          .shutter = "best-phase",
          .simulated = true,
          .world = "nominal",
          .scene = "aero1.jpg",
          .motion = "kite"};
}

TEST(FlightReportTest, TheSummaryCarriesEachFigureUnderItsKey) {
  FlightFigures figures;
  figures.rms_error_px = 3.5;
  figures.frames = 300;
  figures.loop_latency_p99_ms = 4.25;
  figures.silent_gross_pct = 0.5;
  PipelineStats stats;
  stats.dropped = 7;
  stats.servo_outages = 2;
  PhotoFigures photos;
  photos.photos = 3;
  photos.wait_s_mean = 0.75;
  const nlohmann::json summary = FlightSummary(figures, photos, stats, SimulatedKiteFlight());
  EXPECT_DOUBLE_EQ(summary.at("rms_error_px").get<double>(), 3.5);
  EXPECT_EQ(summary.at("frames").get<std::uint64_t>(), 300U);
  EXPECT_DOUBLE_EQ(summary.at("loop_latency_p99_ms").get<double>(), 4.25);
  EXPECT_DOUBLE_EQ(summary.at("silent_gross_pct").get<double>(), 0.5);
  EXPECT_EQ(summary.at("dropped_frames").get<std::uint64_t>(), 7U);
  EXPECT_EQ(summary.at("servo_outages").get<std::uint64_t>(), 2U);
  EXPECT_EQ(summary.at("photos").get<std::size_t>(), 3U);
  EXPECT_DOUBLE_EQ(summary.at("photo_wait_s_mean").get<double>(), 0.75);
  EXPECT_EQ(summary.at("controller"), "predictive");
  EXPECT_EQ(summary.at("shutter"), "best-phase");
  EXPECT_EQ(summary.at("world"), "nominal");
  EXPECT_EQ(summary.at("scene"), "aero1.jpg");
  EXPECT_EQ(summary.at("motion"), "kite");
  EXPECT_EQ(summary.at("simulated"), true);
}

// JSON has no NaN: a figure without truth (hardware, no photos) is null, and the missing
// calibration estimate says why.
TEST(FlightReportTest, AFigureWithoutTruthIsNullAndTheMissingEstimateSaysWhy) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  FlightFigures figures;
  figures.rms_error_px = nan;
  figures.gross_pct = nan;
  figures.deg_per_px_estimate_missing = "not simulated: the true deg/px is unknown";
  const nlohmann::json summary =
      FlightSummary(figures, ComputePhotoFigures({}), PipelineStats{}, SimulatedKiteFlight());
  EXPECT_TRUE(summary.at("rms_error_px").is_null());
  EXPECT_TRUE(summary.at("gross_pct").is_null());
  EXPECT_TRUE(summary.at("deg_per_px_estimate_ratio").is_null());
  EXPECT_TRUE(summary.at("photo_sharpness_mean").is_null());
  EXPECT_EQ(summary.at("deg_per_px_estimate_missing"), figures.deg_per_px_estimate_missing);
  FlightFigures estimated;
  EXPECT_FALSE(FlightSummary(estimated, PhotoFigures{}, PipelineStats{}, SimulatedKiteFlight())
                   .contains("deg_per_px_estimate_missing"));
}

TEST(FlightReportTest, AFlightOnHardwareNamesNoWorldSceneOrMotion) {
  FlightDescription hardware = SimulatedKiteFlight();
  hardware.simulated = false;
  const nlohmann::json summary =
      FlightSummary(FlightFigures{}, PhotoFigures{}, PipelineStats{}, hardware);
  EXPECT_EQ(summary.at("world"), "none");
  EXPECT_EQ(summary.at("scene"), "");
  EXPECT_EQ(summary.at("motion"), "none");
  EXPECT_EQ(summary.at("simulated"), false);
}

// A fixating record of frame `index` holding frame 0's view, `error_px` away in x.
TelemetryRecord Fixating(std::uint64_t index, double error_px, bool lock_lost, bool off_target) {
  TelemetryRecord r;
  r.index = index;
  r.reference_frame = 0;
  r.view_offset_x_px = error_px;
  r.view_offset_y_px = 0.0;
  r.lock_lost = lock_lost;
  r.off_target = off_target;
  return r;
}

// Issue 9's honest lock: a gross frame the agent said was off target (lock held, the view
// trailed) is not silent; one it claimed to hold is, and the lock-held reading counts both.
TEST(FlightReportTest, SilentGrossCountsOnlyFramesClaimedOnTarget) {
  std::vector<TelemetryRecord> records = {Fixating(0, 0, false, false)};
  records.push_back(Fixating(1, 25, false, true));   // trailing, said so
  records.push_back(Fixating(2, 25, false, false));  // claimed on target: silent
  records.push_back(Fixating(3, 25, true, true));    // lost, said so
  records.push_back(Fixating(4, 2, false, false));   // held
  const FlightFigures f = ComputeFlightFigures(records, PipelineStats{});
  EXPECT_DOUBLE_EQ(f.gross_pct, 75.0);
  EXPECT_DOUBLE_EQ(f.silent_gross_pct, 25.0);
  EXPECT_DOUBLE_EQ(f.gross_lock_held_pct, 50.0);
  EXPECT_DOUBLE_EQ(f.off_target_pct, 50.0);
  EXPECT_DOUBLE_EQ(f.lock_lost_pct, 25.0);
}

// A view resumed after a restart was taken in another run: it lies 4 px right of the view of
// the frame that found it (0), so a frame 11 px right of frame 0's view is 7 px off the held
// view, not gross; judged against frame 0's view it would be a silent gross frame.
TEST(FlightReportTest, AResumedViewIsJudgedFromWhereTheResumeFoundIt) {
  std::vector<TelemetryRecord> records = {Fixating(0, 0, false, false),
                                          Fixating(1, 11, false, false)};
  for (TelemetryRecord& r : records) r.reference_seen_at = {4, 0};
  const FlightFigures f = ComputeFlightFigures(records, PipelineStats{});
  EXPECT_DOUBLE_EQ(f.rms_error_px, 7.0);
  EXPECT_DOUBLE_EQ(f.gross_pct, 0.0);
  EXPECT_DOUBLE_EQ(f.silent_gross_pct, 0.0);
}

}  // namespace
}  // namespace kapfix::agent
