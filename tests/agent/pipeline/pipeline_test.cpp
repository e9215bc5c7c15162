// The pipeline's threads with fakes: free-running capture drops stale frames and counts them;
// the watchdog parks the servos when a control step stalls.
#include "agent/pipeline/pipeline.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <thread>

#include "agent/capture/fake_frame_source.hpp"
#include "agent/pipeline/telemetry_recorder.hpp"
#include "agent/servo/fake_servo_driver.hpp"
#include "agent/servo/maestro_servo_driver.hpp"
#include "agent/servo/maestro_usb_settings.hpp"
#include "tests/agent/support/fake_maestro_usb_port.hpp"
#include "tests/agent/support/held_open_servo_driver.hpp"
#include "tests/agent/support/manual_clock.hpp"
#include "tests/agent/support/recording_stream_sink.hpp"

namespace kapfix::agent {
namespace {

// Holds targets at `pan_deg`; sleeps `per_frame` on every frame (slower than the camera). With a
// `clock`, every frame moves it one frame period, and frame `stall_at` moves it `stall` and
// waits until `released` holds (the stall lasts until the test saw what it waits for).
class ScriptedProcessor : public FrameProcessor {
 public:
  double pan_deg = 5.0;
  std::uint64_t stall_at = ~0ull;
  std::chrono::milliseconds stall{0};
  std::chrono::milliseconds per_frame{0};
  std::uint64_t calls = 0;
  testing::ManualClock* clock = nullptr;
  std::function<bool()> released;
  std::function<void(std::uint64_t)> at_frame;  // before frame `calls` is processed

  FrameOutcome Process(const CapturedFrame& /*frame*/, const ServoTargets& /*current*/,
                       double /*dt_s*/) override {
    if (at_frame) at_frame(calls);
    if (clock != nullptr) clock->Advance(std::chrono::milliseconds(33));
    if (calls == stall_at && clock != nullptr) {
      clock->Advance(stall);
      EXPECT_TRUE(testing::WaitUntil(released, std::chrono::seconds(30)))
          << "the stall was never noticed";
    }
    std::this_thread::sleep_for(per_frame);
    ++calls;
    FrameOutcome outcome;
    outcome.step.match.found = true;
    outcome.step.targets = {pan_deg, 0.0};
    outcome.mode = AgentMode::kFixate;
    return outcome;
  }
};

// Records like FakeServoDriver and tells, from any thread, whether the pan servo was sent to
// 0 deg (parked) after it held another angle.
class ParkWatchingServoDriver : public FakeServoDriver {
 public:
  bool SetAngle(ServoAxis axis, double deg, std::string* error) override {
    const bool ok = FakeServoDriver::SetAngle(axis, deg, error);
    if (ok && axis == ServoAxis::kPan) {
      if (deg != 0.0) moved_ = true;
      if (deg == 0.0 && moved_) parked_ = true;
    }
    return ok;
  }
  bool parked() const { return parked_.load(); }

 private:
  std::atomic<bool> moved_{false};
  std::atomic<bool> parked_{false};
};

struct Rig {
  FakeFrameSource* source = nullptr;
  ParkWatchingServoDriver* fake = nullptr;
  std::unique_ptr<FakeFrameSource> source_owner;
  std::unique_ptr<LimitedServoDriver> servos;
  TelemetryRecorder telemetry;

  Rig() {
    source_owner = std::make_unique<FakeFrameSource>(
        std::vector<cv::Mat>{cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(1))});
    source = source_owner.get();
    auto backend = std::make_unique<ParkWatchingServoDriver>();
    fake = backend.get();
    // A clock that moves 1 s per reading: the rate limit never holds a move back, so what the
    // test sees is the pipeline's doing.
    auto ticks = std::make_shared<std::atomic<std::int64_t>>(0);
    servos = std::make_unique<LimitedServoDriver>(
        std::move(backend), ServoLimits{}, ServoLimits{}, [ticks] { return (*ticks += 1'000'000); },
        1.0);
    std::string error;
    EXPECT_TRUE(source->Open(&error)) << error;
    EXPECT_TRUE(servos->Open(&error)) << error;
  }
};

TEST(PipelineTest, FreeRunningCaptureDropsStaleFramesAndCountsThem) {
  Rig rig;
  ScriptedProcessor processor;
  processor.per_frame = std::chrono::milliseconds(2);  // slower than the fake camera
  PipelineOptions options;
  options.frames = 30;
  options.lock_step = false;
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.processed, 30u);
  EXPECT_GT(stats.dropped, 0u);
  // Every grabbed frame was either processed or dropped: indices skip exactly the drops.
  const auto records = rig.telemetry.records();
  ASSERT_EQ(records.size(), 30u);
  std::uint64_t skipped = 0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    ASSERT_GT(records[i].index, records[i - 1].index);
    skipped += records[i].index - records[i - 1].index - 1;
  }
  EXPECT_GT(skipped, 0u);
  // Frames skipped between processed ones were all counted (more may have been dropped after
  // the 30th, before the capture thread saw the stop).
  EXPECT_LE(skipped, stats.dropped);
}

TEST(PipelineTest, LockStepDropsNothing) {
  Rig rig;
  ScriptedProcessor processor;
  PipelineOptions options;
  options.frames = 50;
  options.lock_step = true;
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.processed, 50u);
  EXPECT_EQ(stats.dropped, 0u);
  const auto records = rig.telemetry.records();
  for (std::size_t i = 0; i < records.size(); ++i) EXPECT_EQ(records[i].index, i);
}

// The watchdog runs on a clock the processor moves: one frame period per frame, 600 ms on
// the stalled frame, which then waits until the servos were parked.
TEST(PipelineTest, WatchdogParksTheServosWhenAControlStepStalls) {
  Rig rig;
  testing::ManualClock clock;
  ScriptedProcessor processor;
  processor.clock = &clock;
  processor.stall_at = 5;
  processor.stall = std::chrono::milliseconds(600);
  processor.released = [&rig] { return rig.fake->parked(); };
  PipelineOptions options;
  options.frames = 10;
  options.lock_step = true;
  options.watchdog_ms = 150;
  options.watchdog_clock = clock.AsFunction();
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.watchdog_stalls, 1u);
  // Commands to the pan axis: (Open moves nothing: the fake tells it stands at 0) the loop
  // holds 5 deg, the watchdog parks it during the stall (0), the loop resumes at 5, and the
  // end of the run parks it again.
  std::vector<double> pan;
  for (const FakeServoCommand& c : rig.fake->commands()) {
    if (c.kind == FakeServoCommand::Kind::kSetAngle && c.axis == ServoAxis::kPan) {
      pan.push_back(c.deg);
    }
  }
  ASSERT_GE(pan.size(), 11u);
  EXPECT_EQ(pan.front(), 5.0);
  // Frames 0…4 command 5 deg, then the watchdog's park, then frames 5…9.
  EXPECT_EQ(pan[5], 0.0) << "the watchdog did not park the pan servo during the stall";
  EXPECT_EQ(pan[6], 5.0);
  EXPECT_EQ(pan.back(), 0.0);
}

// Frames one period (33 ms) apart on the watchdog's clock never stall it, however slowly the
// machine runs them.
TEST(PipelineTest, NoStallNoPark) {
  Rig rig;
  testing::ManualClock clock;
  ScriptedProcessor processor;
  processor.clock = &clock;
  PipelineOptions options;
  options.frames = 10;
  options.lock_step = true;
  options.watchdog_ms = 200;
  options.watchdog_clock = clock.AsFunction();
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  EXPECT_EQ(pipeline.Run().watchdog_stalls, 0u);
}

// Start-up that waits for hardware (issue 10): a camera that did not open at start is opened
// by the pipeline with back-off, said in the devices' health (once, not per failed retry), and
// the flight starts once it is there; the servos get their first command only with its first
// frame.
TEST(PipelineTest, ACameraMissingAtStartIsWaitedForThenFlown) {
  Rig rig;
  rig.source->FailOpen(true);
  ScriptedProcessor processor;
  PipelineOptions options;
  options.frames = 5;
  options.lock_step = true;
  options.retry_initial_ms = 1;
  options.camera_open = false;
  options.camera_error = "no camera at start";
  std::vector<DevicesHealth> reports;
  std::atomic<int> waits{0};
  options.on_health = [&reports](const DevicesHealth& health) { reports.push_back(health); };
  // The camera comes up after a few reconnect waits (several failed retries).
  options.on_alive = [&waits, &rig] {
    if (++waits == 20) rig.source->FailOpen(false);
  };
  const std::size_t commands_before = rig.fake->commands().size();
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  EXPECT_EQ(pipeline.health().camera, DeviceHealth::Waiting("no camera at start"));
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.processed, 5u);
  EXPECT_GE(rig.source->open_attempts(), 3) << "the retries the reports must not repeat";
  // The capture thread's own first Open fails with the fake's reason: one report of it, then
  // one of the camera being there.
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports.front().camera.status, DeviceStatus::kWaiting);
  EXPECT_FALSE(reports.front().camera.reason.empty());
  EXPECT_EQ(reports.back().camera, DeviceHealth::Ok());
  EXPECT_EQ(pipeline.health().camera, DeviceHealth::Ok());
  EXPECT_EQ(StatusLine(reports.front()).rfind("camera waiting: ", 0), 0u)
      << StatusLine(reports.front());
  EXPECT_GT(rig.fake->commands().size(), commands_before);
  // Every step's telemetry says the camera was there.
  for (const TelemetryRecord& record : rig.telemetry.records()) {
    EXPECT_EQ(record.camera_health, DeviceHealth::Ok());
  }
}

// Runs `pipeline` on a thread of its own until `back` holds (the servos reported OK again after
// an outage), then stops it: the reopen runs on a worker, so how many frames it takes depends
// on the machine, not on the test.
PipelineStats RunUntilTheServosAreBack(Pipeline& pipeline, const std::atomic<bool>& back) {
  PipelineStats stats;
  std::thread run([&pipeline, &stats] { stats = pipeline.Run(); });
  EXPECT_TRUE(testing::WaitUntil([&back] { return back.load(); }, std::chrono::seconds(30)))
      << "the servo driver never came back";
  pipeline.Stop();
  run.join();
  return stats;
}

// The servos' health rides along every step: lost (with the driver's reason) while the driver
// is out, "reopening" while the worker opens it, OK again once it is back; reported on each
// change, not per frame.
TEST(PipelineTest, TheServosHealthIsLostWhileTheDriverIsOutThenOk) {
  Rig rig;
  ScriptedProcessor processor;
  PipelineOptions options;
  options.lock_step = true;
  options.retry_initial_ms = 1;
  options.retry_max_ms = 2;
  processor.per_frame = std::chrono::milliseconds(1);
  std::vector<DevicesHealth> reports;  // control thread; read after it ended
  std::atomic<bool> back{false};
  options.on_health = [&reports, &back](const DevicesHealth& health) {
    reports.push_back(health);
    if (health.servos == DeviceHealth::Ok()) back = true;
  };
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  rig.fake->Disconnect();  // unplugged before the first frame
  const PipelineStats stats = RunUntilTheServosAreBack(pipeline, back);
  ASSERT_EQ(stats.servo_recoveries, 1U);
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[0].servos.status, DeviceStatus::kLost);
  EXPECT_FALSE(reports[0].servos.reason.empty());
  EXPECT_EQ(reports[1].servos, DeviceHealth::Reopening(reports[0].servos));
  EXPECT_EQ(reports[2].servos, DeviceHealth::Ok());
  const auto records = rig.telemetry.records();
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.front().servo_health.status, DeviceStatus::kLost);
  EXPECT_EQ(records.back().servo_health, DeviceHealth::Ok());
}

TEST(PipelineTest, ALostCameraIsReopenedAndTheFlightResumes) {
  Rig rig;
  ScriptedProcessor processor;
  rig.source->FailNextGrabs(3);
  PipelineOptions options;
  options.frames = 10;
  options.lock_step = true;
  options.retry_initial_ms = 1;
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.processed, 10u);
  EXPECT_EQ(stats.grab_errors, 3u);
  EXPECT_EQ(stats.camera_reconnects, 3u);
  EXPECT_EQ(rig.source->open_count(), 4);  // the first Open and one per outage
  EXPECT_TRUE(stats.error.empty()) << stats.error;
  // The camera numbers its frames from 0 again after each Open; the flight's numbering goes on.
  const auto records = rig.telemetry.records();
  for (std::size_t i = 1; i < records.size(); ++i) {
    EXPECT_GT(records[i].index, records[i - 1].index);
  }
}

// Three frames arm the watchdog, then the camera goes away for good. The outage lasts many
// watchdog timeouts on its clock (two per reconnect wait), and the run ends only after the
// watchdog looked at that clock several times during it.
TEST(PipelineTest, ALongCameraOutageIsNotAControlStall) {
  Rig rig;
  testing::ManualClock clock;
  ScriptedProcessor processor;
  processor.clock = &clock;
  // Lock step: the capture thread waits for this frame's end, so the source is not in use.
  processor.at_frame = [&rig](std::uint64_t call) {
    if (call != 2) return;
    rig.source->FailNextGrabs(1);
    rig.source->FailOpen(true);  // stays unplugged until Stop
  };
  PipelineOptions options;
  options.lock_step = true;
  options.watchdog_ms = 50;
  options.watchdog_clock = clock.AsFunction();
  options.retry_initial_ms = 5;
  options.retry_max_ms = 20;
  Pipeline* running = nullptr;
  std::optional<std::uint64_t> reads_at_outage;
  const std::thread::id control_thread = std::this_thread::get_id();
  options.on_alive = [&] {
    if (std::this_thread::get_id() == control_thread) return;  // a control step
    clock.Advance(std::chrono::milliseconds(2 * 50));
    if (!reads_at_outage) reads_at_outage = clock.reads();
    if (rig.source->open_attempts() >= 4 && clock.reads() >= *reads_at_outage + 3) {
      running->Stop();
    }
  };
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  running = &pipeline;
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.processed, 3u);
  EXPECT_EQ(stats.watchdog_stalls, 0u)
      << "the servos must hold, not park, while the camera is away";
  EXPECT_GE(rig.source->open_attempts(), 4) << "reconnection was retried";
  EXPECT_EQ(stats.camera_reconnects, 0u);
}

TEST(PipelineTest, AFailedServoDriverIsReopenedAndTheFlightResumes) {
  Rig rig;
  ScriptedProcessor processor;
  PipelineOptions options;
  options.lock_step = true;
  options.retry_initial_ms = 1;
  options.retry_max_ms = 2;
  processor.per_frame = std::chrono::milliseconds(1);
  std::atomic<bool> back{false};
  options.on_health = [&back](const DevicesHealth& health) {
    if (health.servos == DeviceHealth::Ok()) back = true;
  };
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  rig.fake->Disconnect();  // unplugged before the first frame
  const PipelineStats stats = RunUntilTheServosAreBack(pipeline, back);
  EXPECT_EQ(stats.servo_outages, 1U);
  EXPECT_EQ(stats.servo_recoveries, 1U);
  const auto records = rig.telemetry.records();
  ASSERT_FALSE(records.empty());
  // The control loop went on through the outage: steps were recorded with the servos out.
  EXPECT_NE(records.front().servo_health, DeviceHealth::Ok());
  // Fixation resumed: the last frames' targets reached the servos.
  EXPECT_EQ(records.back().servo_health, DeviceHealth::Ok());
  EXPECT_DOUBLE_EQ(records.back().angle_pan_deg, processor.pan_deg);
}

// Issue 11, the control thread never waits: the servo driver fails and its reopen then blocks
// inside the device's Open until the test releases it. Control steps go on meanwhile (20 of
// them while the device is still inside Open), the health says "reopening", and once released
// the driver is taken up and fixation goes on.
TEST(PipelineTest, ControlStepsGoOnWhileTheServoDriverIsReopened) {
  FakeFrameSource source(std::vector<cv::Mat>{cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(1))});
  ASSERT_TRUE(source.Open(nullptr));
  auto backend = std::make_unique<testing::HeldOpenServoDriver>();
  testing::HeldOpenServoDriver* fake = backend.get();
  auto ticks = std::make_shared<std::atomic<std::int64_t>>(0);
  LimitedServoDriver servos(
      std::move(backend), ServoLimits{}, ServoLimits{}, [ticks] { return (*ticks += 1'000'000); },
      1.0);
  ASSERT_TRUE(servos.Open(nullptr));
  fake->Disconnect();  // unplugged before the first frame
  fake->Hold();
  ScriptedProcessor processor;
  processor.per_frame = std::chrono::milliseconds(1);
  std::atomic<std::uint64_t> steps{0};
  processor.at_frame = [&steps](std::uint64_t /*frame*/) { ++steps; };
  PipelineOptions options;
  options.lock_step = true;
  options.retry_initial_ms = 1;
  options.retry_max_ms = 2;
  TelemetryRecorder telemetry;
  Pipeline pipeline(source, servos, processor, {&telemetry}, options);
  PipelineStats stats;
  std::thread run([&pipeline, &stats] { stats = pipeline.Run(); });

  const auto wait = std::chrono::seconds(30);  // a bound, not a pace: each wait ends on its event
  EXPECT_TRUE(testing::WaitUntil([fake] { return fake->opening(); }, wait));
  const std::uint64_t at_open = steps.load();
  EXPECT_TRUE(testing::WaitUntil([&steps, at_open] { return steps.load() >= at_open + 20; }, wait))
      << "the control loop waited for the device";
  EXPECT_TRUE(fake->opening()) << "the device was released before the steps were counted";
  EXPECT_TRUE(pipeline.health().servos.reopening()) << pipeline.health().servos.reason;
  fake->Release();
  EXPECT_TRUE(testing::WaitUntil(
      [&pipeline] { return pipeline.health().servos == DeviceHealth::Ok(); }, wait));
  pipeline.Stop();
  run.join();
  EXPECT_EQ(stats.servo_outages, 1U);
  EXPECT_EQ(stats.servo_recoveries, 1U);
  EXPECT_EQ(stats.watchdog_stalls, 0U);
  const auto records = telemetry.records();
  ASSERT_FALSE(records.empty());
  EXPECT_DOUBLE_EQ(records.back().angle_pan_deg, processor.pan_deg) << "fixation went on";
}

TEST(PipelineTest, WithoutReconnectionALostCameraEndsTheRunWithItsReason) {
  Rig rig;
  ScriptedProcessor processor;
  rig.source->FailNextGrabs(1);
  PipelineOptions options;
  options.frames = 10;
  options.reconnect_camera = false;
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.processed, 0u);
  EXPECT_FALSE(stats.error.empty());
}

}  // namespace
}  // namespace kapfix::agent

namespace kapfix::agent {
namespace {

// The camera's gain as each frame was processed. Lock step: the capture thread waits while a
// frame is processed, so the fake camera is read between its calls.
struct GainPerFrame {
  std::vector<float> gains;
  void Watch(ScriptedProcessor* processor, const FakeFrameSource* source) {
    processor->at_frame = [this, source](std::uint64_t) {
      gains.push_back(source->applied().gain_db());
    };
  }
};

kapfix::v1::CameraSettings Gain(float db) {
  kapfix::v1::CameraSettings settings;
  settings.set_gain_db(db);
  return settings;
}

TEST(PipelineTest, TheCameraSettingsAreAppliedBeforeTheFirstFrame) {
  Rig rig;
  ScriptedProcessor processor;
  GainPerFrame seen;
  seen.Watch(&processor, rig.source);
  PipelineOptions options;
  options.frames = 2;
  options.lock_step = true;
  options.camera_settings = Gain(6);
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  pipeline.Run();
  EXPECT_EQ(seen.gains, (std::vector<float>{6, 6}));
}

TEST(PipelineTest, ANewGainReachesTheCameraThroughTheSettingsMessage) {
  Rig rig;
  ScriptedProcessor processor;
  GainPerFrame seen;
  PipelineOptions options;
  options.frames = 6;
  options.lock_step = true;
  options.camera_settings = Gain(6);
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  processor.at_frame = [&](std::uint64_t frame) {
    seen.gains.push_back(rig.source->applied().gain_db());
    if (frame == 2) pipeline.SetCameraSettings(Gain(12));  // as a settings command does
  };
  pipeline.Run();
  // Frame 3 was grabbed after the change: the capture thread applied it first.
  EXPECT_EQ(seen.gains, (std::vector<float>{6, 6, 6, 12, 12, 12}));
}

TEST(PipelineTest, AReopenedCameraGetsTheLatestSettingsNotTheConfiguredOnes) {
  Rig rig;
  ScriptedProcessor processor;
  GainPerFrame seen;
  PipelineOptions options;
  options.frames = 6;
  options.lock_step = true;
  options.retry_initial_ms = 1;
  options.camera_settings = Gain(6);
  Pipeline pipeline(*rig.source, *rig.servos, processor, {&rig.telemetry}, options);
  processor.at_frame = [&](std::uint64_t frame) {
    seen.gains.push_back(rig.source->applied().gain_db());
    if (frame == 1) pipeline.SetCameraSettings(Gain(12));
    if (frame == 3) rig.source->FailNextGrabs(1);  // lost; its Open forgets the settings
  };
  const PipelineStats stats = pipeline.Run();
  EXPECT_EQ(stats.camera_reconnects, 1u);
  EXPECT_EQ(seen.gains, (std::vector<float>{6, 6, 12, 12, 12, 12}));
}

}  // namespace
}  // namespace kapfix::agent
