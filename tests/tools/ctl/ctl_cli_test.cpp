// kapfix-ctl as a script runs it (popen), against the fake agent in this process: exit codes,
// printed lines, files.
#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/photo_sidecar.hpp"
#include "kapfix/v1/telemetry.pb.h"
#include "link/envelope.hpp"
#include "link/session_reader.hpp"
#include "link/topic_table.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

struct Outcome {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Publishes telemetry every 5 ms while it lives, as a flying agent does.
class TelemetryPump {
 public:
  explicit TelemetryPump(kapfix::agent::StreamPublisher& publisher)
      : thread_([this, &publisher] {
          for (std::uint64_t frame = 0; !stop_.load(); ++frame) {
            kapfix::v1::Telemetry telemetry;
            telemetry.set_frame_number(frame);
            telemetry.set_mode(kapfix::v1::MODE_FIXATE);
            publisher.Publish(telemetry);
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
          }
        }) {}
  ~TelemetryPump() {
    stop_.store(true);
    thread_.join();
  }
  TelemetryPump(const TelemetryPump&) = delete;
  TelemetryPump& operator=(const TelemetryPump&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

class CtlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (std::filesystem::temp_directory_path() / "kapfix_ctl_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    folder_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  // Runs kapfix-ctl with the link options pointing at `agent` (or at `port` for both sockets).
  Outcome Run(const std::string& args) {
    return RunRaw("--agent 127.0.0.1 --command-port " +
                  std::to_string(PortOf(agent_.command_endpoint)) + " --stream-port " +
                  std::to_string(PortOf(agent_.stream_endpoint)) + " --timeout 2000 " + args);
  }

  Outcome RunRaw(const std::string& args) {
    const ProcessOutcome run =
        RunProcess(std::string(KAPFIX_CTL) + " " + args, folder_ / "stderr.txt");
    return {run.exit_code, run.out, run.err};
  }

  FakeAgent agent_;
  std::filesystem::path folder_;
};

TEST_F(CtlTest, StatusPrintsTheModeAndSettingsAndExitsZero) {
  const auto outcome = Run("status");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, HasSubstr("mode: idle"));
  EXPECT_THAT(outcome.out, HasSubstr("search: strategy=h23"));
  EXPECT_THAT(outcome.out, HasSubstr("slice: 0 of 9"));
}

TEST_F(CtlTest, StatusJsonPrintsTheAgentState) {
  const auto outcome = Run("status --json");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, HasSubstr("\"frameWidthPx\": 640"));
}

TEST_F(CtlTest, SetSendsTheValueAndExitsZero) {
  const auto outcome = Run("set p 0.25");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_FLOAT_EQ(agent_.control.State().gains().p(), 0.25F);
}

TEST_F(CtlTest, SetNanGainExitsOneWithTheAgentsReason) {
  const auto outcome = Run("set p nan");
  EXPECT_EQ(outcome.exit_code, 1);
  EXPECT_THAT(outcome.err, HasSubstr("agent refused: set_gains.p = nan"));
  EXPECT_THAT(outcome.err, HasSubstr("ERROR_CODE_OUT_OF_RANGE"));
}

TEST_F(CtlTest, SetUnknownKeyExitsTwo) {
  const auto outcome = Run("set warp_speed 9");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("unknown key 'warp_speed'"));
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CtlTest, SetUnreadableValueExitsTwo) {
  const auto outcome = Run("set exposure fast");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CtlTest, SliceThatIsNotANumberExitsTwo) { EXPECT_EQ(Run("slice three").exit_code, 2); }

TEST_F(CtlTest, SliceBeyondTheSliceCountExitsOne) {
  const auto outcome = Run("slice 12");
  EXPECT_EQ(outcome.exit_code, 1);
  EXPECT_THAT(outcome.err, HasSubstr("select_slice = 12"));
}

TEST_F(CtlTest, SlicePicksTheSlice) {
  EXPECT_EQ(Run("slice 4").exit_code, 0);
  EXPECT_EQ(agent_.control.State().slice(), 4U);
}

TEST_F(CtlTest, FixateSwitchesTheAgentToFixate) {
  const auto outcome = Run("fixate");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_EQ(agent_.control.State().mode(), kapfix::v1::MODE_FIXATE);
}

TEST_F(CtlTest, AgentRefusalExitsOneAndPrintsItsReason) {
  agent_.control.RefuseWith(kapfix::v1::ERROR_CODE_WRONG_MODE, "calibrate first");
  const auto outcome = Run("fixate");
  EXPECT_EQ(outcome.exit_code, 1);
  EXPECT_THAT(outcome.err, HasSubstr("calibrate first"));
}

TEST_F(CtlTest, NothingListeningExitsThree) {
  UnusedPort port;
  const std::string p = std::to_string(port.port());
  const auto outcome = RunRaw("--agent 127.0.0.1 --command-port " + p + " --stream-port " + p +
                              " --timeout 300 status");
  EXPECT_EQ(outcome.exit_code, 3);
  EXPECT_THAT(outcome.err, HasSubstr("no answer"));
}

TEST_F(CtlTest, WatchPrintsCountTelemetryLines) {
  TelemetryPump pump(agent_.publisher);
  const auto outcome = Run("watch --count 3");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  std::istringstream lines(outcome.out);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    EXPECT_THAT(line, StartsWith("telemetry seq="));
    EXPECT_THAT(line, HasSubstr("mode=fixate"));
  }
  EXPECT_EQ(count, 3);
}

TEST_F(CtlTest, WatchSummaryCountsTheTelemetryAndItsSequenceGapsInOneLine) {
  TelemetryPump pump(agent_.publisher);
  const auto outcome = Run("watch --duration 0.5 --summary");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, StartsWith("watch telemetry="));
  EXPECT_THAT(outcome.out, HasSubstr(" sequence_gaps=0 dropped_by_agent=0 seconds="));
  EXPECT_EQ(std::count(outcome.out.begin(), outcome.out.end(), '\n'), 1);
}

TEST_F(CtlTest, WatchExitsThreeWhenNothingListens) {
  UnusedPort port;
  const std::string p = std::to_string(port.port());
  const auto outcome = RunRaw("--agent 127.0.0.1 --command-port " + p + " --stream-port " + p +
                              " --timeout 300 watch");
  EXPECT_EQ(outcome.exit_code, 3);
}

TEST_F(CtlTest, SspWaitFollowsTheReportsAndPrintsTheRecommendedSlice) {
  const auto outcome = Run("ssp --wait");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, HasSubstr("ssp progress=50/100"));
  EXPECT_THAT(outcome.out, HasSubstr("recommended_slice: 3"));
  EXPECT_EQ(agent_.control.State().mode(), kapfix::v1::MODE_SSP);
}

// `ssp --frames` is made from SetMode.deadline_frames's schema option (its flag and help).
TEST_F(CtlTest, SspFramesSendsTheDeadline) {
  const auto outcome = Run("ssp --frames 150");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  const auto commands = agent_.control.commands();
  ASSERT_FALSE(commands.empty());
  EXPECT_EQ(commands.back().set_mode().deadline_frames(), 150U);
}

TEST_F(CtlTest, SspWithoutFramesLeavesTheAgentsDeadline) {
  const auto outcome = Run("ssp");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  const auto commands = agent_.control.commands();
  ASSERT_FALSE(commands.empty());
  EXPECT_FALSE(commands.back().set_mode().has_deadline_frames());
}

TEST_F(CtlTest, SspFramesOutOfRangeExitsOneWithTheAgentsReason) {
  const auto outcome = Run("ssp --frames 1");
  EXPECT_EQ(outcome.exit_code, 1);
  EXPECT_THAT(outcome.err, HasSubstr("set_mode.deadline_frames = 1: must be in [2, 1e+05] frames"));
}

TEST_F(CtlTest, SspFramesThatIsNotANumberExitsTwo) {
  const auto outcome = Run("ssp --frames many");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr("--frames: cannot read 'many'"));
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CtlTest, SspHelpShowsTheDeadlinesHelpFromTheSchema) {
  const auto outcome = RunRaw("ssp --help");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, HasSubstr("--frames"));
  EXPECT_THAT(outcome.out,
              HasSubstr("deadline of PSS, SSP and free-swing recording, [2, 1e+05] frames"));
}

TEST_F(CtlTest, PhotoSaveWritesTheAgentsPhotoToTheFolder) {
  const auto outcome = Run("photo --save " + folder_.string());
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  const auto path = folder_ / FakeAgentControl::kPhotoName;
  EXPECT_THAT(outcome.out, HasSubstr(path.string()));
  EXPECT_EQ(ReadFile(path), FakeAgentControl::PhotoBytes());
}

// Issue 13: the sidecar is written beside the photo, as the agent's store writes it.
TEST_F(CtlTest, PhotoSaveWritesTheSidecarBesideThePhoto) {
  const auto outcome = Run("photo --save " + folder_.string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  const auto sidecar = folder_ / (std::string(FakeAgentControl::kPhotoName) + ".json");
  const std::string json = ReadFile(sidecar);
  kapfix::v1::PhotoMetadata metadata;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(json, &metadata).ok()) << json;
  EXPECT_EQ(metadata.file_name(), FakeAgentControl::kPhotoName);
  EXPECT_EQ(metadata.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(metadata.view_speed_px_per_frame(), 0.75F);
  EXPECT_EQ(json, kapfix::v1::PhotoSidecarJson(metadata));
}

TEST_F(CtlTest, PhotoSaveIntoAMissingFolderMakesIt) {
  const auto folder = folder_ / "missing" / "deeper";
  const auto outcome = Run("photo --save " + folder.string());
  ASSERT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_EQ(ReadFile(folder / FakeAgentControl::kPhotoName), FakeAgentControl::PhotoBytes());
  EXPECT_TRUE(
      std::filesystem::exists(folder / (std::string(FakeAgentControl::kPhotoName) + ".json")));
}

TEST_F(CtlTest, PhotoSaveWhereAFileIsInTheWayExitsTwo) {
  const auto file = folder_ / "a-file";
  std::ofstream(file) << "not a folder";
  const auto outcome = Run("photo --save " + file.string());
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_THAT(outcome.err, HasSubstr(file.string()));
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CtlTest, ResyncPrintsTheStateAndSavesThePhotosTheAgentResends) {
  agent_.control.HoldStoredPhoto();
  const auto outcome = Run("resync --photos-since-us 1 --save " + folder_.string());
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_THAT(outcome.out, HasSubstr("gains: controller=pid p=0.8 "));
  EXPECT_THAT(outcome.out, HasSubstr("resync photos_resent=1 photos_saved=1 seconds="));
  EXPECT_EQ(ReadFile(folder_ / FakeAgentControl::kPhotoName), FakeAgentControl::PhotoBytes());
  const auto commands = agent_.control.commands();
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].request_state().resend_photos_since_us(), 1);
  EXPECT_TRUE(commands[0].request_state().resend_slice_report());
}

TEST_F(CtlTest, ResyncAskingForPhotosWithoutAFolderExitsTwo) {
  EXPECT_EQ(Run("resync --photos-since-us 1").exit_code, 2);
  EXPECT_TRUE(agent_.control.commands().empty());
}

TEST_F(CtlTest, RecordWritesEveryReceivedMessageLengthPrefixed) {
  TelemetryPump pump(agent_.publisher);
  const auto file = folder_ / "session.kfx";
  const auto outcome = Run("record " + file.string() + " --count 20");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  kapfix::link::SessionReader reader(file.string());
  int messages = 0;
  while (const auto message = reader.Next()) {
    auto decoded = kapfix::link::NewMessageForTopic(message->topic);
    ASSERT_NE(decoded, nullptr) << message->topic;
    std::string error;
    EXPECT_TRUE(kapfix::link::DecodeEnvelope(message->topic, message->payload, decoded.get(),
                                             kapfix::v1::kMaxMessageBytes, &error))
        << error;
    ++messages;
  }
  EXPECT_TRUE(reader.error().empty()) << reader.error();
  EXPECT_EQ(messages, 20);
}

TEST_F(CtlTest, HelpDocumentsTheExitCodesAndExitsZero) {
  const auto outcome = RunRaw("--help");
  EXPECT_EQ(outcome.exit_code, 0);
  EXPECT_THAT(outcome.out, HasSubstr("1  the agent refused"));
  EXPECT_THAT(outcome.out, HasSubstr("3  no answer within --timeout"));
}

TEST_F(CtlTest, MissingSubcommandExitsTwo) { EXPECT_EQ(RunRaw("").exit_code, 2); }

}  // namespace
}  // namespace kapfix::testing
