// Google Benchmark of one search on a fixed pair of 300×300 frames (aero1.jpg moved by 37 px),
// per strategy and sampling, next to cv::matchTemplate on the same pair. Complements
// kapfix-bench-matcher (which runs whole swings) with stable per-call figures for profiling,
// and the roll reads: the off-target claim's for a patch off the frame centre, and the
// tracking's from the region around the patch (every confident frame of fixation).
#include <benchmark/benchmark.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "bench/peer_matchers.hpp"
#include "common/fixation/patch_roll.hpp"
#include "common/fixation/region_roll_reader.hpp"
#include "common/image/color_channel.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix::bench {
namespace {

struct FramePair {
  cv::Mat reference;
  cv::Mat current;
};

const FramePair& Pair() {
  static const FramePair pair = [] {
    const cv::Mat photo =
        cv::imread(std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg", cv::IMREAD_COLOR);
    if (photo.empty()) throw std::runtime_error("aero1.jpg missing: install opencv-doc");
    const cv::Mat plane = ExtractChannel(photo, ColorChannel::kGreen);
    return FramePair{plane(cv::Rect(150, 100, 300, 300)).clone(),
                     plane(cv::Rect(150 - 37, 100, 300, 300)).clone()};
  }();
  return pair;
}

void RunSearch(benchmark::State& state, const SearchStrategy& strategy, SamplingOptions sampling) {
  const FramePair& pair = Pair();
  const ReferencePatch reference(pair.reference,
                                 SampleSet({cv::Rect(100, 100, 100, 100)}, sampling));
  SearchResult result;
  for (auto _ : state) {
    result = strategy.Search(reference, pair.current, {});
    benchmark::DoNotOptimize(result);
  }
  if (result.shift.x != 37) state.SkipWithError("wrong shift");
  state.counters["pixels"] = static_cast<double>(result.pixels_compared);
}

void BM_Strategy(benchmark::State& state, const std::string& name, SamplingOptions sampling) {
  std::string error;
  const auto strategy = MakeSearchStrategy(name, &error);
  RunSearch(state, *strategy, sampling);
}

void BM_MatchTemplate(benchmark::State& state) {
  RunSearch(state, MatchTemplatePeer(), {SamplingKind::kAll});
}

// The roll read for the off-target claim (FixationLoop, a patch off the frame centre): what it
// adds to a frame's search, on the same pair (no roll, so it must read ~0).
void BM_ReadPatchRoll(benchmark::State& state) {
  const FramePair& pair = Pair();
  std::optional<PatchRoll> read;
  for (auto _ : state) {
    read = ReadPatchRoll(pair.reference, cv::Rect(100, 100, 100, 100), pair.current, {37, 0}, {});
    benchmark::DoNotOptimize(read);
  }
  if (!read || std::abs(read->roll_rad) > 0.005) state.SkipWithError("wrong roll");
}

// The roll tracking's read (RollingReference, each confident frame): aero1.jpg's middle
// 640×480 turned by 4° about the centre patch, read from level at the right displacement.
void BM_RegionRollRead(benchmark::State& state) {
  const cv::Mat photo =
      cv::imread(std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg", cv::IMREAD_COLOR);
  const cv::Mat plane = ExtractChannel(photo, ColorChannel::kGreen);
  const cv::Rect frame((plane.cols - 640) / 2, (plane.rows - 480) / 2, 640, 480);
  const cv::Mat reference = plane(frame).clone();
  const cv::Rect patch(270, 190, 100, 100);
  const cv::Mat current = TurnedPlane(reference, {319.5, 239.5}, 4);
  const RegionRollReader reader(reference, patch, {});
  std::optional<RegionRoll> read;
  for (auto _ : state) {
    read = reader.Read(current, {0, 0}, 0);
    benchmark::DoNotOptimize(read);
  }
  if (!read || std::abs(read->roll_deg - 4) > 0.2) state.SkipWithError("wrong roll");
}

BENCHMARK_CAPTURE(BM_Strategy, all_all, "all", SamplingOptions{SamplingKind::kAll});
BENCHMARK_CAPTURE(BM_Strategy, h23_random10, "h23", SamplingOptions{SamplingKind::kRandom, 0.1});
BENCHMARK_CAPTURE(BM_Strategy, h15_random10, "h15", SamplingOptions{SamplingKind::kRandom, 0.1});
BENCHMARK_CAPTURE(BM_Strategy, pyr_random10, "pyr", SamplingOptions{SamplingKind::kRandom, 0.1});
BENCHMARK_CAPTURE(BM_Strategy, h23_all, "h23", SamplingOptions{SamplingKind::kAll});
BENCHMARK(BM_MatchTemplate);
BENCHMARK(BM_ReadPatchRoll);
BENCHMARK(BM_RegionRollRead);

}  // namespace
}  // namespace kapfix::bench

// One core, as on the platform's board: OpenCV's thread pool only adds scheduling noise on
// frames this small, for us and for the peers alike.
int main(int argc, char** argv) {
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
