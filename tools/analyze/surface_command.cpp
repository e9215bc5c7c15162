// `kapfix-analyze surface`: the chapter-3 study of one photo — the error surface of a patch
// layout over the whole frame and the success-rate map of the descent controller (SPEC §2.9,
// thesis Table 3.2).
#include <algorithm>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "common/analysis/success_rate_map.hpp"
#include "common/image/color_channel.hpp"
#include "common/matching/error_surface.hpp"
#include "common/sampling/patch_layout.hpp"
#include "tools/analyze/command.hpp"
#include "tools/analyze/progress_reporter.hpp"
#include "tools/analyze/swing_setup.hpp"

namespace kapfix::analyze {
namespace {

struct SurfaceArgs {
  std::string image;
  int patch = 100;
  int frame = 300;
  std::string sampling = "random:0.1";
  std::string layout = "central";
  std::string channel = "green";
  std::uint32_t seed = 1;
  int max_steps = 500;
  bool thesis_pixels = false;
};

cv::Mat Heatmap(const cv::Mat& values) {
  cv::Mat finite;
  values.convertTo(finite, CV_32F);  // patchNaNs takes single precision only
  cv::patchNaNs(finite, 0.0);
  cv::Mat normalised;
  cv::normalize(finite, normalised, 0, 255, cv::NORM_MINMAX, CV_8U);
  cv::Mat colored;
  cv::applyColorMap(normalised, colored, cv::COLORMAP_VIRIDIS);
  cv::resize(colored, colored, cv::Size(), 2, 2, cv::INTER_NEAREST);
  return colored;
}

// The command line checked and turned into the study's settings.
struct SurfaceSetup {
  PatchLayout layout = PatchLayout::kCentral;
  ColorChannel channel = ColorChannel::kGreen;
  SamplingOptions sampling;
  int patch_side = 0;  // [px]
  DescentOptions descent;
};

SurfaceSetup ParseSurfaceArgs(const SurfaceArgs& args) {
  SurfaceSetup setup;
  const auto layout = ParsePatchLayout(args.layout);
  if (!layout) {
    throw std::invalid_argument("--layout: expected central, individuals or merge, got '" +
                                args.layout + "'");
  }
  setup.layout = *layout;
  const auto channel = ParseColorChannel(args.channel);
  if (!channel) throw std::invalid_argument("--channel: expected green, rgb or rgb-sum");
  setup.channel = *channel;
  std::string error;
  if (!ParseSamplingOptions(args.sampling, &setup.sampling, &error)) {
    throw std::invalid_argument("--sampling: " + error);
  }
  setup.sampling.seed = args.seed;
  setup.patch_side = args.patch;
  if (args.thesis_pixels) {
    if (setup.sampling.kind == SamplingKind::kAll || setup.layout != PatchLayout::kCentral) {
      throw std::invalid_argument(
          "--thesis-pixels: Table 3.2 used static or random sampling of one central patch");
    }
    const ThesisSurfaceSampling thesis = ThesisTable32Sampling(setup.sampling.kind, args.seed);
    setup.sampling = thesis.sampling;
    setup.patch_side = thesis.patch_side;
  }
  setup.descent.max_steps = args.max_steps;
  if (!setup.descent.IsValid(&error)) throw std::invalid_argument(error);
  return setup;
}

// surface.csv (distance and success per shift), the two images and steps_histogram.csv.
void WriteSurfaceFiles(const ErrorSurface& surface, const SuccessRateMap& map, int range,
                       ReportWriter& report) {
  std::vector<double> dx;
  std::vector<double> dy;
  std::vector<double> distance;
  std::vector<double> success;
  for (int y = -range; y <= range; ++y) {
    for (int x = -range; x <= range; ++x) {
      dx.push_back(x);
      dy.push_back(y);
      distance.push_back(surface.At(x, y));
      success.push_back(map.success.at<std::uint8_t>(y + range, x + range));
    }
  }
  report.WriteCsv("surface.csv", {"dx", "dy", "distance", "success"}, {dx, dy, distance, success});
  report.WritePng("surface.png", Heatmap(surface.distance));
  cv::Mat success_image;
  map.success.convertTo(success_image, CV_8U, 255.0);
  cv::resize(success_image, success_image, cv::Size(), 2, 2, cv::INTER_NEAREST);
  report.WritePng("success_map.png", success_image);
  std::vector<double> steps;
  std::vector<double> counts;
  for (const auto& [s, n] : map.steps_histogram) {
    steps.push_back(s);
    counts.push_back(n);
  }
  report.WriteCsv("steps_histogram.csv", {"steps", "starts"}, {steps, counts});
}

nlohmann::json RunSurface(const SurfaceArgs& args, ReportWriter& report) {
  const SurfaceSetup setup = ParseSurfaceArgs(args);
  const cv::Mat frame = SquareFrame(LoadScene(args.image), args.frame);
  const cv::Mat plane = ExtractChannel(frame, setup.channel);
  if (setup.patch_side + 4 > args.frame) {
    throw std::invalid_argument("the " + std::to_string(setup.patch_side) +
                                "-px patch leaves no room to shift in a " +
                                std::to_string(args.frame) + "-px frame (needs at least " +
                                std::to_string(setup.patch_side + 4) + ")");
  }
  const std::vector<cv::Rect> patches =
      MakePatchLayout(setup.layout, frame.size(), setup.patch_side);
  int range = args.frame;
  for (const cv::Rect& r : patches) {
    range = std::min({range, r.x, r.y, frame.cols - r.br().x, frame.rows - r.br().y});
  }
  if (range < 2) throw std::invalid_argument("the patches leave no room to shift in the frame");
  const ReferencePatch reference(plane, SampleSet(patches, setup.sampling));

  ProgressReporter surface_progress("error surface");
  const ErrorSurface surface = ComputeErrorSurface(
      reference, plane, range, [&](int done, int total) { surface_progress.Update(done, total); });
  ProgressReporter map_progress("success-rate map");
  const SuccessRateMap map = ComputeSuccessRateMap(
      surface, setup.descent, [&](int done, int total) { map_progress.Update(done, total); });
  WriteSurfaceFiles(surface, map, range, report);

  const cv::Point minimum = surface.ArgMin();
  return {{"image", args.image},
          {"layout", ToString(setup.layout)},
          {"sampling", ToString(setup.sampling)},
          {"frame", args.frame},
          {"range_px", range},
          {"sampled_pixels", reference.size()},
          {"patch", setup.patch_side},
          {"starts", map.starts},
          {"success_pct", map.success_pct},
          {"global_minimum", {minimum.x, minimum.y}},
          {"steps_histogram", map.steps_histogram}};
}

}  // namespace

void AddSurfaceCommand(CLI::App& app, OutputArgs* output, CommandRun* run) {
  auto args = std::make_shared<SurfaceArgs>();
  CLI::App* command = app.add_subcommand(
      "surface", "Error surface and descent success-rate map of a photo (thesis chapter 3)");
  command->add_option("--image", args->image, "Photo to study")->required();
  command->add_option("--patch", args->patch, "Central patch side [px]")
      ->capture_default_str()
      ->check(CLI::Range(4, 4000));
  command->add_option("--frame", args->frame, "Side of the square frame the photo is cut to [px]")
      ->capture_default_str()
      ->check(CLI::Range(32, 4000));
  command->add_option("--sampling", args->sampling, "all, static, random or random:F")
      ->capture_default_str();
  command->add_option("--layout", args->layout, "central, individuals or merge")
      ->capture_default_str();
  command->add_option("--channel", args->channel, "green, rgb or rgb-sum")->capture_default_str();
  command->add_option("--seed", args->seed, "Seed of the random sampling")->capture_default_str();
  command->add_option("--max-steps", args->max_steps, "Descent step limit per start")
      ->capture_default_str();
  command->add_flag("--thesis-pixels", args->thesis_pixels,
                    "Table 3.2's pixel counts: static 14,600 or random 2,500 on one patch");
  AddOutputOptions(command, output);
  command->callback(
      [args, run] { *run = [args](ReportWriter& report) { return RunSurface(*args, report); }; });
}

}  // namespace kapfix::analyze
