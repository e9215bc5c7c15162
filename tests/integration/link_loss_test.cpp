// Issue 5, link loss with the mock station: the real agent (simulation, real time) loses its
// station — a kapfix-ctl process, SIGKILLed — for 60 s. It must fly on with its last settings,
// keep saving photos and keep its memory bounded; the returning station (kapfix-ctl resync) is
// resynchronised within 2 s: settings, latest SSP result, every photo taken meanwhile.
// The outage is flown once (about 75 s) and each test checks one behaviour on it, so CTest runs
// this executable as a single test (see CMakeLists.txt).
#include <gmock/gmock.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "kapfix/v1/photo.pb.h"
#include "tests/integration/agent_process.hpp"
#include "tests/integration/child_process.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

constexpr auto kOutage = std::chrono::seconds(60);
constexpr double kPhotoIntervalS = 3;  // [s] of camera time, which is real time here
constexpr double kCameraFps = 30;      // [frames/s] the built-in simulated camera's rate
// [1] share of the camera's frames the agent must fly in real time: a loaded machine may lag.
constexpr double kRealTimeShare = 0.8;
// [s] issue 5's requirement, from starting the returning station to its last photo saved.
constexpr double kResyncLimitS = 2.0;
// [kB] RSS growth allowed over the outage. The agent keeps nothing per frame, per photo or per
// message while no station listens: its PUB drops what nobody subscribed to, photos go to disk.
// What can still move is bounded: up to 8 queued photo frames (PhotoTaker, 640×480×3 bytes =
// 0.9 MB each), the JPEG encoder's buffers, and malloc keeping freed blocks — 8 MB covers
// those; a leak of one frame per second would be 55 MB.
constexpr long kRssMarginKb = 8 * 1024;
// [px] fixation figures: the predictive controller leaves under 3 px rms (issue 3); a view
// that is not held drifts by the swing's 100 px (SPEC §3). A single frame may catch a gust
// (10.3 px seen on one photo), so single frames get a wider limit, still far from a drift.
constexpr double kFixationRmsLimitPx = 5;
constexpr double kFixationPeakLimitPx = 20;

long RssKb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

std::int64_t NowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// The sidecars of the photos in `folder`, by file name.
std::map<std::string, kapfix::v1::PhotoMetadata> Photos(const std::filesystem::path& folder) {
  std::map<std::string, kapfix::v1::PhotoMetadata> photos;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (entry.path().extension() != ".json") continue;
    kapfix::v1::PhotoMetadata metadata;
    if (google::protobuf::util::JsonStringToMessage(ReadFile(entry.path()), &metadata).ok()) {
      photos[metadata.file_name()] = metadata;
    }
  }
  return photos;
}

// One telemetry line of kapfix-ctl watch / resync, as numbers.
struct TelemetryLine {
  std::uint64_t frame = 0;
  std::string mode;
  double dx = 0;  // [px]
  double dy = 0;  // [px]
  bool lock_lost = false;
};

std::vector<TelemetryLine> TelemetryLines(const std::string& text) {
  static const std::regex kLine(
      R"(telemetry seq=\d+ frame=(\d+) mode=(\w+) dx=(\S+) dy=(\S+) .*lock_lost=(\d))");
  std::vector<TelemetryLine> lines;
  std::istringstream in(text);
  std::string line;
  std::smatch match;
  while (std::getline(in, line)) {
    if (!std::regex_search(line, match, kLine)) continue;
    lines.push_back({std::stoull(match[1]), match[2], std::stod(match[3]), std::stod(match[4]),
                     match[5] == "1"});
  }
  return lines;
}

// The flight: set up with a station, lose it for kOutage, bring it back.
struct Outage {
  Outage() { Fly(); }
  void Fly();

  AgentProcess agent{{"--mode", "idle"}};
  std::string problem;           // why the flight could not be flown as planned; empty when it was
  int slice = 0;                 // SSP's recommendation, then fixated on
  std::uint64_t frame_lost = 0;  // telemetry frame number the station last saw
  std::int64_t lost_us = 0;      // [µs since epoch] when the station was killed
  std::size_t photos_before = 0;
  std::size_t photos_after = 0;
  std::vector<long> rss_kb;  // [kB] sampled through the outage, first ~1 s in
  bool alive_after = false;
  std::int64_t returned_us = 0;   // [µs since epoch] when the station came back
  std::filesystem::path station;  // the returning station's photo folder
  AgentProcess::CtlOutcome resync;
  double resync_s = 0;  // [s] wall clock of the whole kapfix-ctl resync run
  AgentProcess::CtlOutcome watch_after;
};

void Outage::Fly() {
  const auto step = [this](const std::string& args) {
    const auto outcome = agent.Ctl(args);
    if (outcome.exit_code != 0 && problem.empty()) {
      problem = "kapfix-ctl " + args + " → " + std::to_string(outcome.exit_code) + ": " +
                outcome.err + "\nagent log:\n" + agent.log();
    }
    return outcome;
  };
  step("set photo_interval " + std::to_string(kPhotoIntervalS));
  step("set p 0.95");
  const auto ssp = step("ssp --wait --frames 45");
  std::smatch match;
  if (!std::regex_search(ssp.out, match, std::regex("recommended_slice: (\\d+)"))) {
    if (problem.empty()) problem = "no recommendation in: " + ssp.out;
    return;
  }
  slice = std::stoi(match[1]);
  step("slice " + std::to_string(slice));
  if (!problem.empty()) return;

  // The station that will be lost: a watching kapfix-ctl, up until its telemetry flows.
  const std::filesystem::path station_out = agent.folder() / "station.out";
  ChildProcess lost_station(agent.CtlCommand({"watch"}), station_out,
                            agent.folder() / "station.err");
  const auto connect_deadline = Clock::now() + std::chrono::seconds(10);
  while (TelemetryLines(ReadFile(station_out)).size() < 30 && Clock::now() < connect_deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  lost_us = NowUs();
  lost_station.Stop(SIGKILL);
  const auto seen = TelemetryLines(ReadFile(station_out));
  if (seen.size() < 30) {
    problem = "the station saw no telemetry before it was lost";
    return;
  }
  frame_lost = seen.back().frame;
  photos_before = Photos(agent.photos()).size();

  const auto outage_start = Clock::now();
  std::this_thread::sleep_for(std::chrono::seconds(1));
  while (Clock::now() - outage_start < kOutage) {
    rss_kb.push_back(RssKb(agent.pid()));
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
  rss_kb.push_back(RssKb(agent.pid()));
  alive_after = agent.running();
  photos_after = Photos(agent.photos()).size();

  station = agent.folder() / "returned_station";
  std::filesystem::create_directories(station);
  returned_us = NowUs();
  const auto resync_start = Clock::now();
  resync = agent.Ctl("resync --photos-since-us " + std::to_string(lost_us) + " --save " +
                     station.string());
  resync_s = std::chrono::duration<double>(Clock::now() - resync_start).count();
  watch_after = agent.Ctl("watch --count 90");

  // The figures, for the record (README, issue 5).
  std::ostringstream rss;
  for (const long kb : rss_kb) rss << kb << " ";
  const std::size_t resync_line = resync.out.rfind("resync ");
  std::cout << "link loss figures: resync " << resync_s << " s (whole kapfix-ctl run); photos on "
            << "the agent " << photos_before << " before the outage, " << photos_after
            << " after; VmRSS [kB] every 2 s through the outage: " << rss.str() << "\n"
            << (resync_line == std::string::npos ? "" : resync.out.substr(resync_line))
            << std::flush;
}

const Outage& TheOutage() {
  static Outage outage;  // flown by the first test that asks
  return outage;
}

// Each test starts with this: a flight that could not be set up fails every test.
#define REQUIRE_FLOWN(outage) ASSERT_TRUE((outage).problem.empty()) << (outage).problem

TEST(LinkLossTest, AgentFliesOnInRealTimeWhileTheStationIsGone) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  EXPECT_TRUE(outage.alive_after) << outage.agent.log();
  const auto after = TelemetryLines(outage.watch_after.out);
  ASSERT_FALSE(after.empty()) << outage.watch_after.err;
  const double outage_frames = kCameraFps * static_cast<double>(kOutage.count());
  EXPECT_GE(static_cast<double>(after.front().frame - outage.frame_lost),
            kRealTimeShare * outage_frames);
}

TEST(LinkLossTest, AgentKeepsSavingPhotosWhileTheStationIsGone) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  std::size_t during = 0;
  const std::int64_t outage_us = std::chrono::microseconds(kOutage).count();
  for (const auto& [name, metadata] : Photos(outage.agent.photos())) {
    const std::int64_t t = metadata.capture_time_us() - outage.lost_us;
    if (t >= 0 && t < outage_us) ++during;
  }
  // One every 3 s of camera time for 60 s: 20. The camera may lag the wall clock by 20 % on a
  // loaded machine (as in the test above), and one photo may straddle each end.
  const double expected = static_cast<double>(kOutage.count()) / kPhotoIntervalS;
  EXPECT_GE(static_cast<double>(during), std::floor(kRealTimeShare * expected) - 1)
      << "photos before " << outage.photos_before << ", after " << outage.photos_after;
  EXPECT_LE(static_cast<double>(during), expected + 1);
}

TEST(LinkLossTest, AgentHoldsTheChosenSliceWhileTheStationIsGone) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  // The photos' sidecars are the record of the outage: slice and displacement at capture.
  std::vector<double> errors;  // [px]
  std::ostringstream listed;
  for (const auto& [name, metadata] : Photos(outage.agent.photos())) {
    if (metadata.capture_time_us() < outage.lost_us) continue;
    EXPECT_EQ(metadata.slice(), static_cast<unsigned>(outage.slice)) << name;
    const auto& d = metadata.displacement();
    errors.push_back(std::hypot(static_cast<double>(d.x_px()) + d.x_subpx(),
                                static_cast<double>(d.y_px()) + d.y_subpx()));
    listed << name << ": " << errors.back() << " px\n";
  }
  ASSERT_FALSE(errors.empty());
  double sum_sq = 0;
  for (const double e : errors) sum_sq += e * e;
  EXPECT_LE(std::sqrt(sum_sq / static_cast<double>(errors.size())), kFixationRmsLimitPx)
      << listed.str();
  EXPECT_LE(*std::max_element(errors.begin(), errors.end()), kFixationPeakLimitPx) << listed.str();
}

TEST(LinkLossTest, AgentMemoryStaysBoundedWhileTheStationIsGone) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  ASSERT_GE(outage.rss_kb.size(), 2U);
  std::ostringstream samples;
  for (const long kb : outage.rss_kb) samples << kb << " ";
  EXPECT_GT(outage.rss_kb.front(), 0);
  // The allocator's working set swings by ~8 MB from one sample to the next (photos encoded,
  // video frames queued), so one sample against another measures the swing. What is held for
  // the missing station grows with the outage: the peak of the second half against the peak of
  // the first.
  const auto middle = outage.rss_kb.begin() + static_cast<std::ptrdiff_t>(outage.rss_kb.size() / 2);
  const long first_peak = *std::max_element(outage.rss_kb.begin(), middle);
  const long second_peak = *std::max_element(middle, outage.rss_kb.end());
  EXPECT_LE(second_peak - first_peak, kRssMarginKb) << "VmRSS [kB] every 2 s: " << samples.str();
}

TEST(LinkLossTest, ReturningStationIsResynchronisedWithinTwoSeconds) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  ASSERT_EQ(outage.resync.exit_code, 0) << outage.resync.err << outage.agent.log();
  EXPECT_LE(outage.resync_s, kResyncLimitS) << outage.resync.out;
}

TEST(LinkLossTest, ReturningStationGetsTheLastSettings) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  ASSERT_EQ(outage.resync.exit_code, 0) << outage.resync.err;
  EXPECT_THAT(outage.resync.out, HasSubstr("mode: fixate\n"));
  EXPECT_THAT(outage.resync.out, HasSubstr("slice: " + std::to_string(outage.slice) + " of "));
  EXPECT_THAT(outage.resync.out, HasSubstr(" p=0.95 "));
  EXPECT_THAT(outage.resync.out, HasSubstr(" interval_s=3\n"));
}

TEST(LinkLossTest, ReturningStationGetsTheLatestSspResult) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  ASSERT_EQ(outage.resync.exit_code, 0) << outage.resync.err;
  EXPECT_THAT(outage.resync.out, HasSubstr("slice index=1 rank="));
  EXPECT_THAT(outage.resync.out, HasSubstr("recommended_slice: " + std::to_string(outage.slice)));
}

TEST(LinkLossTest, ReturningStationGetsEveryPhotoTakenMeanwhileIntact) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  ASSERT_EQ(outage.resync.exit_code, 0) << outage.resync.err;
  std::vector<std::string> taken;  // while the station was gone
  for (const auto& [name, metadata] : Photos(outage.agent.photos())) {
    const std::int64_t t = metadata.capture_time_us();
    if (t >= outage.lost_us && t < outage.returned_us) taken.push_back(name);
  }
  ASSERT_FALSE(taken.empty());
  for (const std::string& name : taken) {
    const std::filesystem::path received = outage.station / name;
    ASSERT_TRUE(std::filesystem::exists(received)) << name << " not received\n"
                                                   << outage.resync.out;
    EXPECT_EQ(ReadFile(received), ReadFile(outage.agent.photos() / name)) << name;
  }
}

TEST(LinkLossTest, FixationErrorIsSmallOnceTheStationIsBack) {
  const Outage& outage = TheOutage();
  REQUIRE_FLOWN(outage);
  const auto lines = TelemetryLines(outage.watch_after.out);
  ASSERT_EQ(lines.size(), 90U) << outage.watch_after.err;
  double sum_sq = 0;
  for (const TelemetryLine& line : lines) {
    EXPECT_EQ(line.mode, "fixate");
    EXPECT_FALSE(line.lock_lost) << "frame " << line.frame;
    sum_sq += line.dx * line.dx + line.dy * line.dy;
  }
  const double rms = std::sqrt(sum_sq / static_cast<double>(lines.size()));
  EXPECT_LE(rms, kFixationRmsLimitPx) << outage.watch_after.out;
}

}  // namespace
}  // namespace kapfix::testing
