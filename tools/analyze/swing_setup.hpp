#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "common/evaluation/swing_recording.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix::analyze {

// The options shared by the subcommands that fly the open-loop swing of SPEC §3.
struct SwingArgs {
  std::string image;
  int frames = 400;
  std::uint32_t seed = 1;
  std::string size = "300x300";  // frame W×H [px]
  std::string channel = "green";
  std::string sampling = "random:0.1";
  std::string axis = "x";
  int patch = 100;  // [px]
  bool gusts = false;
  double jitter_px = 2.0;  // σ of the pendulum's Y jitter [px] (SPEC §3)
  double noise = 3.0;      // σ of the sensor noise [grey levels]
  bool no_subpixel = false;
  // The thesis's methods as printed: literal hierarchical searches, whole-pixel answers.
  // Combinations the thesis did not define are refused (MakeStrategy).
  bool literal = false;
};

void AddSwingOptions(CLI::App* command, SwingArgs* args);

// Where the patch sits: slice `slice` (1 = top) of `slices` horizontal bands.
struct SliceArgs {
  int slice = 5;
  int slices = 9;
};
void AddSliceOptions(CLI::App* command, SliceArgs* args);

// "a,b,,c" → {"a", "b", "c"}: the comma-separated lists of --strategies, --pool, --only.
std::vector<std::string> SplitCommaList(const std::string& text);

// Reads the scene photo; throws std::runtime_error naming the file when it cannot.
cv::Mat LoadScene(const std::string& path);

// The photo scaled so that its shorter side is `side`, then its centre square: the thesis
// studied 300×300 frames (chapter 3).
cv::Mat SquareFrame(const cv::Mat& photo, int side);

// Validated settings from the flags; throws std::invalid_argument with the reason.
SwingOptions MakeSwingOptions(const SwingArgs& args);
ColorChannel MakeColorChannel(const SwingArgs& args);
SamplingOptions MakeSampling(const SwingArgs& args);
SearchOptions MakeSearchOptions(const SwingArgs& args);
std::unique_ptr<SearchStrategy> MakeStrategy(const std::string& name);
// The strategy as the flags ask: MakeLiteralSearchStrategy with --literal (refusing what the
// thesis did not define, with the reason), MakeStrategy otherwise.
std::unique_ptr<SearchStrategy> MakeStrategy(const SwingArgs& args, const std::string& name);

// Renders the swing once, with progress on stderr, and warns there when the scene had to be
// upscaled to cover the swing.
SwingRecording RecordSwingWithProgress(const SwingArgs& args);

}  // namespace kapfix::analyze
