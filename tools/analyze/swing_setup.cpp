#include "tools/analyze/swing_setup.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "common/search/literal_hierarchical_search.hpp"
#include "tools/analyze/progress_reporter.hpp"

namespace kapfix::analyze {

void AddSwingOptions(CLI::App* command, SwingArgs* args) {
  command->add_option("--image", args->image, "Scene photo the virtual camera looks at")
      ->required();
  command->add_option("--frames", args->frames, "Frames of swing to simulate")
      ->capture_default_str()
      ->check(CLI::Range(2, 100000));
  command->add_option("--seed", args->seed, "Seed of noise, jitter and sampling")
      ->capture_default_str();
  command->add_option("--size", args->size, "Frame size WxH [px]")->capture_default_str();
  command
      ->add_option("--channel", args->channel,
                   "green, rgb (per-channel SSD, as the thesis) or rgb-sum (SSD of B+G+R)")
      ->capture_default_str();
  command->add_option("--sampling", args->sampling, "all, static, random or random:F")
      ->capture_default_str();
  command->add_option("--axis", args->axis, "Search axis: x, y or both")->capture_default_str();
  command->add_option("--patch", args->patch, "Patch side [px]")
      ->capture_default_str()
      ->check(CLI::Range(8, 2000));
  command->add_flag("--gusts", args->gusts, "Add random gusts to the pendulum");
  command->add_option("--jitter", args->jitter_px, "Sigma of the swing's Y jitter [px]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 50.0));
  command->add_option("--noise", args->noise, "Sigma of the sensor noise [grey levels]")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  command->add_flag("--no-subpixel", args->no_subpixel, "Integer shifts only (as the thesis)");
  command->add_flag("--literal", args->literal,
                    "The thesis's searches as printed: level-3 answer, whole pixels, visits as "
                    "the thesis counts them");
}

void AddSliceOptions(CLI::App* command, SliceArgs* args) {
  command->add_option("--slice", args->slice, "Slice holding the patch (1 = top)")
      ->capture_default_str()
      ->check(CLI::Range(1, 99));
  command->add_option("--slices", args->slices, "Number of slices")
      ->capture_default_str()
      ->check(CLI::Range(1, 99));
}

std::vector<std::string> SplitCommaList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

cv::Mat LoadScene(const std::string& path) {
  if (!std::filesystem::exists(path))
    throw std::runtime_error("cannot read '" + path + "': no such file");
  cv::Mat scene = cv::imread(path, cv::IMREAD_COLOR);
  if (scene.empty())
    throw std::runtime_error("cannot read '" + path + "': not an image OpenCV can decode");
  return scene;
}

cv::Mat SquareFrame(const cv::Mat& photo, int side) {
  const double scale = static_cast<double>(side) / std::min(photo.cols, photo.rows);
  cv::Mat scaled;
  cv::resize(photo, scaled, cv::Size(), scale, scale,
             scale < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
  const cv::Rect centre((scaled.cols - side) / 2, (scaled.rows - side) / 2, side, side);
  return scaled(centre).clone();
}

SwingOptions MakeSwingOptions(const SwingArgs& args) {
  SwingOptions options;
  int w = 0;
  int h = 0;
  char tail = 0;
  if (std::sscanf(args.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 ||
      w > 8000 || h > 8000) {
    throw std::invalid_argument("--size: expected WxH between 16 and 8000, got '" + args.size +
                                "'");
  }
  options.camera.frame_size = {w, h};
  options.camera.seed = args.seed;
  options.motion.seed = args.seed;
  options.motion.gusts = args.gusts;
  options.motion.jitter_sigma_px = args.jitter_px;
  options.camera.noise_sigma = args.noise;
  options.frames = args.frames;
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  return options;
}

ColorChannel MakeColorChannel(const SwingArgs& args) {
  const auto channel = ParseColorChannel(args.channel);
  if (!channel)
    throw std::invalid_argument("--channel: expected green, rgb or rgb-sum, got '" + args.channel +
                                "'");
  return *channel;
}

SamplingOptions MakeSampling(const SwingArgs& args) {
  SamplingOptions sampling;
  std::string error;
  if (!ParseSamplingOptions(args.sampling, &sampling, &error)) {
    throw std::invalid_argument("--sampling: " + error);
  }
  sampling.seed = args.seed;
  return sampling;
}

SearchOptions MakeSearchOptions(const SwingArgs& args) {
  SearchOptions options;
  const auto axis = ParseSearchAxis(args.axis);
  if (!axis) throw std::invalid_argument("--axis: expected x, y or both, got '" + args.axis + "'");
  options.axis = *axis;
  options.subpixel = !args.no_subpixel && !args.literal;
  return options;
}

std::unique_ptr<SearchStrategy> MakeStrategy(const std::string& name) {
  std::string error;
  auto strategy = MakeSearchStrategy(name, &error);
  if (!strategy) throw std::invalid_argument("--strategy: " + error);
  return strategy;
}

std::unique_ptr<SearchStrategy> MakeStrategy(const SwingArgs& args, const std::string& name) {
  if (!args.literal) return MakeStrategy(name);
  if (MakeColorChannel(args) == ColorChannel::kRgbSum) {
    // The SSD of the sum B + G + R is ours, not the thesis's: it scores (255, 0, 0) against
    // (0, 255, 0) as equal.
    throw std::invalid_argument(
        "--literal: the thesis defines no rgb-sum distance (the SSD of B+G+R); use --channel "
        "green or rgb (the thesis's per-channel SSD)");
  }
  std::string error;
  auto strategy = MakeLiteralSearchStrategy(name, MakeSearchOptions(args), &error);
  if (!strategy) throw std::invalid_argument(error);
  return strategy;
}

SwingRecording RecordSwingWithProgress(const SwingArgs& args) {
  const cv::Mat scene = LoadScene(args.image);
  const SwingOptions options = MakeSwingOptions(args);
  ProgressReporter progress("rendering swing");
  SwingRecording recording =
      RecordSwing(scene, options, MakeColorChannel(args),
                  [&](int done, int total) { progress.Update(done, total); });
  if (recording.upscale_factor > 1.0) {
    std::fprintf(stderr, "note: scene '%s' (%dx%d) upscaled x%.2f to cover the swing\n",
                 args.image.c_str(), scene.cols, scene.rows, recording.upscale_factor);
  }
  return recording;
}

}  // namespace kapfix::analyze
