// A finished calibration is stored by the worker, not on the control thread that reports it
// (issue 11): the report returns while the disk is held up, and the file follows.
#include <gtest/gtest.h>

#include <string>

#include "agent/commands/calibration_store.hpp"
#include "agent/commands/state_keeper.hpp"
#include "agent/worker/work_queue.hpp"
#include "tests/agent/support/gate.hpp"
#include "tests/agent/support/recording_stream_sink.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::Gate;
using kapfix::agent::testing::RecordingStreamSink;
using kapfix::testing::TempDir;

TEST(StateKeeperCalibrationSaveTest, AFinishedCalibrationIsStoredByTheWorkerNotTheReporter) {
  TempDir temp;
  RecordingStreamSink sink;
  const CalibrationStore store(temp.path() / "calibration");
  const AgentConfig config;
  StateKeeper keeper(config, sink, true, nullptr, &store);
  WorkQueue worker("disk writer", 4);
  keeper.StoreCalibrationsOn(&worker);
  Gate disk;  // a write ahead of the calibration's that the disk holds up
  ASSERT_TRUE(worker.Post(
      "slow write",
      [&]() -> WorkQueue::Result {
        disk.Pass();
        return nullptr;
      },
      nullptr));
  disk.WaitEntered();

  kapfix::v1::CalibrationReport report;
  report.set_lens_profile(config.lens);
  report.set_finished(true);
  keeper.OnCalibrationReport(report, LensCalibration{0.05, 0.06});  // returns: nothing waits
  EXPECT_TRUE(disk.holding());
  EXPECT_DOUBLE_EQ(keeper.settings()->active_lens().DegPerPxPan(), 0.05);  // in force at once
  std::string why;
  EXPECT_FALSE(store.Load(config.lens, &why).has_value());  // not written yet

  disk.Open();
  worker.Flush();
  const std::optional<LensCalibration> stored = store.Load(config.lens, &why);
  ASSERT_TRUE(stored.has_value()) << why;
  EXPECT_DOUBLE_EQ(stored->pan_deg_per_px, 0.05);
  EXPECT_DOUBLE_EQ(stored->tilt_deg_per_px, 0.06);
}

}  // namespace
}  // namespace kapfix::agent
