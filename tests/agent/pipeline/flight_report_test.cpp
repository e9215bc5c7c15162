#include "agent/pipeline/flight_report.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace kapfix::agent {
namespace {

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

}  // namespace
}  // namespace kapfix::agent
