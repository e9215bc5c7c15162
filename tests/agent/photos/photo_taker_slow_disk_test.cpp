// The control thread never waits for the disk (issue 11): a photo whose write (fsync) is held
// up by a slow store does not hold up the control steps after it; the photo is still stored
// under the name its reply gave once the store lets it through; photos asked for while the
// writer is full are refused with the reason, and none that was taken is lost.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "agent/capture/fake_frame_source.hpp"
#include "agent/photos/photo_store.hpp"
#include "agent/photos/photo_taker.hpp"
#include "agent/pipeline/pipeline.hpp"
#include "agent/servo/fake_servo_driver.hpp"
#include "tests/agent/support/gate.hpp"
#include "tests/agent/support/recording_stream_sink.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::Gate;
using kapfix::agent::testing::RecordingStreamSink;
using kapfix::testing::TempDir;

// A disk whose fsync takes as long as the test wants: every write waits for the gate.
class SlowPhotoStore : public PhotoStore {
 public:
  using PhotoStore::PhotoStore;
  Gate disk;

  kapfix::v1::PhotoMetadata SaveFile(const std::string& bytes,
                                     kapfix::v1::PhotoMetadata metadata) override {
    disk.Pass();
    return PhotoStore::SaveFile(bytes, std::move(metadata));
  }
};

// Holds the servos; on frame `wait_at` waits until the store is blocked in a write, so that
// every later step runs while the write is still held up.
class WaitingProcessor : public FrameProcessor {
 public:
  explicit WaitingProcessor(Gate& disk) : disk_(disk) {}
  std::uint64_t wait_at = 3;
  std::uint64_t steps_while_blocked = 0;

  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double /*dt_s*/) override {
    if (frame.index == wait_at) disk_.WaitEntered();
    if (disk_.holding()) ++steps_while_blocked;
    FrameOutcome outcome;
    outcome.step.targets = current;
    return outcome;
  }

 private:
  Gate& disk_;
};

struct Rig {
  TempDir temp;
  SlowPhotoStore store{temp.path() / "photos"};
  RecordingStreamSink sink;
  PhotoTaker taker{store, sink, [] { return std::string("6mm"); }};
  FakeFrameSource source{std::vector<cv::Mat>{cv::Mat(48, 64, CV_8UC3, cv::Scalar(40, 90, 160))}};
  std::unique_ptr<LimitedServoDriver> servos;

  Rig() {
    servos = std::make_unique<LimitedServoDriver>(
        std::make_unique<FakeServoDriver>(), ServoLimits{}, ServoLimits{}, SteadyClockNowUs, 1.0);
    std::string error;
    EXPECT_TRUE(source.Open(&error)) << error;
    EXPECT_TRUE(servos->Open(&error)) << error;
  }

  PipelineStats Fly(FrameProcessor& processor, std::uint64_t frames) {
    PipelineOptions options;
    options.frames = frames;
    options.lock_step = true;
    options.park_wait = [] {};
    Pipeline pipeline(source, *servos, processor, {&taker}, options);
    return pipeline.Run();
  }
};

TEST(PhotoTakerSlowDiskTest, ControlStepsGoOnWhileAPhotoWriteIsHeldUp) {
  Rig rig;
  std::string error;
  std::string name;
  ASSERT_TRUE(rig.taker.Request("slow disk", &error, &name)) << error;
  WaitingProcessor processor(rig.store.disk);
  constexpr std::uint64_t kFrames = 20;
  const PipelineStats stats = rig.Fly(processor, kFrames);
  // Every step ran, most of them while the photo's write was blocked, and the write still is.
  EXPECT_EQ(stats.processed, kFrames);
  EXPECT_GE(processor.steps_while_blocked, kFrames - processor.wait_at);
  EXPECT_TRUE(rig.store.disk.holding());
  EXPECT_EQ(rig.taker.saved(), 0u);
  EXPECT_FALSE(std::filesystem::exists(rig.store.dir() / name));

  rig.store.disk.Open();  // the fsync returns
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), 1u);
  EXPECT_TRUE(std::filesystem::exists(rig.store.dir() / name)) << name;
}

TEST(PhotoTakerSlowDiskTest, PhotosAskedForWhileTheWriterIsFullAreRefusedAndNoneTakenIsLost) {
  Rig rig;
  WaitingProcessor processor(rig.store.disk);
  processor.wait_at = 1;
  std::string error;
  std::vector<std::string> names(1);
  ASSERT_TRUE(rig.taker.Request("first", &error, &names[0])) << error;
  rig.Fly(processor, 2);  // the first photo is taken and its write blocks
  ASSERT_TRUE(rig.store.disk.holding());
  // More photos than the writer may queue, while the disk is stuck.
  std::string refusal;
  for (int i = 0; i < 50 && refusal.empty(); ++i) {
    std::string name;
    if (rig.taker.Request("more", &refusal, &name)) names.push_back(name);
  }
  EXPECT_NE(refusal.find("photo refused"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("still being taken or written"), std::string::npos) << refusal;
  EXPECT_LT(names.size(), 50u);
  rig.Fly(processor, 2);  // the accepted requests are taken on the next frame
  rig.store.disk.Open();
  rig.taker.Flush();
  EXPECT_EQ(rig.taker.saved(), names.size());
  EXPECT_EQ(rig.taker.failed(), 0u);
  for (const std::string& name : names) {
    EXPECT_TRUE(std::filesystem::exists(rig.store.dir() / name)) << name;
  }
}

}  // namespace
}  // namespace kapfix::agent
