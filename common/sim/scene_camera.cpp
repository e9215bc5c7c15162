#include "common/sim/scene_camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "common/sim/sim_random.hpp"

namespace kapfix {
namespace {

constexpr std::uint64_t kNoiseStream = 0x6e6f697365;   // "noise"
constexpr std::uint64_t kRollStream = 0x726f6c6c;      // "roll"
constexpr std::uint64_t kExposureStream = 0x6578706f;  // "expo"
constexpr double kRollPeriodA = 97;                    // [frames] the roll's slow component
constexpr double kRollPeriodB = 31;                    // [frames] and its faster one
constexpr int kExposureStepFrames = 125;               // [frames] between exposure steps
// [1/px per rad of roll] keystone: the image's scale changes by this × roll × distance from
// the centre along y (0.8 % at 150 px for 3° of roll).
constexpr double kKeystonePerRad = 1e-3;
constexpr int kMaxFrameSide = 20000;  // [px] sanity bound on frame_size

bool Finite(double v) { return std::isfinite(v); }

cv::Mat ToBgr(const cv::Mat& scene) {
  if (scene.empty()) throw std::invalid_argument("SceneCamera: the scene image is empty");
  cv::Mat bgr;
  switch (scene.type()) {
    case CV_8UC3:
      bgr = scene.clone();
      break;
    case CV_8UC1:
      cv::cvtColor(scene, bgr, cv::COLOR_GRAY2BGR);
      break;
    case CV_8UC4:
      cv::cvtColor(scene, bgr, cv::COLOR_BGRA2BGR);
      break;
    default:
      throw std::invalid_argument("SceneCamera: the scene must be 8-bit BGR, grey or BGRA");
  }
  return bgr;
}

}  // namespace

bool SceneCameraOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (frame_size.width < 1 || frame_size.height < 1 || frame_size.width > kMaxFrameSide ||
      frame_size.height > kMaxFrameSide) {
    return fail("frame size must be 1…" + std::to_string(kMaxFrameSide) + " px per side, got " +
                std::to_string(frame_size.width) + "×" + std::to_string(frame_size.height));
  }
  if (!Finite(noise_sigma) || noise_sigma < 0) {
    return fail("noise σ must be ≥ 0 grey levels, got " + std::to_string(noise_sigma));
  }
  if (!(brightness_amplitude >= 0 && brightness_amplitude < 1)) {
    return fail("brightness amplitude must be in [0, 1), got " +
                std::to_string(brightness_amplitude));
  }
  if (!Finite(brightness_period_frames) || brightness_period_frames <= 0) {
    return fail("brightness period must be > 0 frames, got " +
                std::to_string(brightness_period_frames));
  }
  if (!Finite(blur_sigma) || blur_sigma < 0) {
    return fail("blur σ must be ≥ 0 px, got " + std::to_string(blur_sigma));
  }
  if (!(roll_max_deg >= 0 && roll_max_deg <= 30)) {
    return fail("roll must be 0…30 deg, got " + std::to_string(roll_max_deg));
  }
  if (!(exposure_step_max >= 0 && exposure_step_max <= 0.5)) {
    return fail("exposure step must be 0…0.5, got " + std::to_string(exposure_step_max));
  }
  if (!(motion_blur_exposure >= 0 && motion_blur_exposure <= 1)) {
    return fail("motion blur exposure must be 0…1 frame, got " +
                std::to_string(motion_blur_exposure));
  }
  if (!(max_excursion_px >= 0 && max_excursion_px <= kMaxFrameSide)) {
    return fail("max excursion must be 0…" + std::to_string(kMaxFrameSide) + " px, got " +
                std::to_string(max_excursion_px));
  }
  return true;
}

SceneCamera::SceneCamera(const cv::Mat& scene_bgr, SceneCameraOptions options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("SceneCamera: " + error);
  cv::Mat scene = ToBgr(scene_bgr);
  const int excursion = static_cast<int>(std::ceil(options_.max_excursion_px));
  // At an excursion of e the window's far edge samples scene x = (cols − 1)/2 + e + (W − 1)/2,
  // which is the last column exactly when cols = W + 2e: no extra margin is needed.
  const int need_w = options_.frame_size.width + 2 * excursion;
  const int need_h = options_.frame_size.height + 2 * excursion;
  const double factor = std::max(
      {1.0, static_cast<double>(need_w) / scene.cols, static_cast<double>(need_h) / scene.rows});
  if (factor > 1.0) {
    // Uniform scale keeps the scene's proportions; ceil and max keep both sides ≥ needed.
    const cv::Size size(std::max(need_w, static_cast<int>(std::ceil(scene.cols * factor))),
                        std::max(need_h, static_cast<int>(std::ceil(scene.rows * factor))));
    cv::resize(scene, scene_, size, 0, 0, cv::INTER_CUBIC);
    upscale_factor_ = factor;
  } else {
    scene_ = scene;
  }
}

double SceneCamera::BrightnessGain(int frame) const {
  return 1.0 + options_.brightness_amplitude *
                   std::sin(2.0 * std::numbers::pi * frame / options_.brightness_period_frames);
}

double SceneRollDeg(const SceneCameraOptions& options, int frame) {
  if (options.roll_max_deg == 0.0) return 0.0;
  const double two_pi = 2.0 * std::numbers::pi;
  const double a = two_pi * SimUniform(options.seed, kRollStream, 0);
  const double b = two_pi * SimUniform(options.seed, kRollStream, 1);
  // Starts level, so the reference frame is not rolled; |roll| ≤ roll_max_deg.
  const double wave = 0.7 * (std::sin(two_pi * frame / kRollPeriodA + a) - std::sin(a)) +
                      0.3 * (std::sin(two_pi * frame / kRollPeriodB + b) - std::sin(b));
  return std::clamp(0.5 * wave, -1.0, 1.0) * options.roll_max_deg;
}

double SceneCamera::ExposureGain(int frame) const {
  if (options_.exposure_step_max == 0.0 || frame < kExposureStepFrames) return 1.0;
  const int step = frame / kExposureStepFrames;
  const double u = SimUniform(options_.seed, kExposureStream, step);
  return 1.0 + options_.exposure_step_max * (2.0 * u - 1.0);
}

cv::Mat SceneCamera::Capture(int frame, cv::Point2d line_of_sight, cv::Point2d motion_px) const {
  if (!Finite(line_of_sight.x) || !Finite(line_of_sight.y)) {
    throw std::invalid_argument("SceneCamera::Capture: line of sight must be finite");
  }
  const cv::Size size = options_.frame_size;
  // Scene coordinate of the window's top-left pixel. Pixel centres sit on integers, so the
  // centre of an N-pixel span starting at o is o + (N − 1)/2.
  double ox = (scene_.cols - 1) / 2.0 + line_of_sight.x - (size.width - 1) / 2.0;
  double oy = (scene_.rows - 1) / 2.0 + line_of_sight.y - (size.height - 1) / 2.0;
  // Far outside the scene every pixel is a replicated border pixel whichever the distance;
  // clamping there changes nothing and keeps warpAffine's fixed-point maths from overflowing.
  ox = std::clamp(ox, -size.width - 2.0, scene_.cols + 2.0);
  oy = std::clamp(oy, -size.height - 2.0, scene_.rows + 2.0);
  cv::Mat window;
  const double roll_rad = RollDeg(frame) * std::numbers::pi / 180.0;
  if (roll_rad == 0.0) {
    const cv::Matx23d to_scene(1, 0, ox, 0, 1, oy);
    cv::warpAffine(scene_, window, to_scene, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REPLICATE);
  } else {
    // Frame pixel → centred → keystone → rotated → scene: the view turns about its centre.
    const double cx = (size.width - 1) / 2.0, cy = (size.height - 1) / 2.0;
    const cv::Matx33d centre(1, 0, -cx, 0, 1, -cy, 0, 0, 1);
    const cv::Matx33d keystone(1, 0, 0, 0, 1, 0, 0, kKeystonePerRad * roll_rad, 1);
    const double c = std::cos(roll_rad), s = std::sin(roll_rad);
    const cv::Matx33d rotate(c, -s, 0, s, c, 0, 0, 0, 1);
    const cv::Matx33d place(1, 0, ox + cx, 0, 1, oy + cy, 0, 0, 1);
    const cv::Matx33d to_scene = place * rotate * keystone * centre;
    cv::warpPerspective(scene_, window, to_scene, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                        cv::BORDER_REPLICATE);
  }

  const double gain = BrightnessGain(frame) * ExposureGain(frame);
  const cv::Point2d smear = motion_px * options_.motion_blur_exposure;
  const bool blur_motion = std::hypot(smear.x, smear.y) >= 1.0;
  if (gain == 1.0 && options_.blur_sigma == 0.0 && options_.noise_sigma == 0.0 && !blur_motion) {
    return window;
  }
  // Float between the steps, so that gain, blur and noise round to 8 bit once.
  cv::Mat work;
  window.convertTo(work, CV_32FC3, gain);
  if (blur_motion) {
    // A line kernel along the motion: the content moved by −smear in the frame while the
    // shutter was open (the sign does not matter for a symmetric smear).
    const double length = std::hypot(smear.x, smear.y);
    const int half = static_cast<int>(std::ceil(length / 2.0));
    cv::Mat kernel = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
    const int samples = 4 * (2 * half + 1);
    for (int i = 0; i < samples; ++i) {
      const double f = static_cast<double>(i) / (samples - 1) - 0.5;  // −½ … ½
      const double x = half + f * smear.x, y = half + f * smear.y;
      const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
      const double fx = x - x0, fy = y - y0;
      for (int dy = 0; dy <= 1; ++dy) {
        for (int dx = 0; dx <= 1; ++dx) {
          const int kx = std::min(x0 + dx, 2 * half), ky = std::min(y0 + dy, 2 * half);
          kernel.at<float>(ky, kx) += static_cast<float>((dx ? fx : 1 - fx) * (dy ? fy : 1 - fy));
        }
      }
    }
    kernel /= cv::sum(kernel)[0];
    cv::filter2D(work, work, -1, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  }
  if (options_.blur_sigma > 0.0) {
    cv::GaussianBlur(work, work, cv::Size(0, 0), options_.blur_sigma, options_.blur_sigma,
                     cv::BORDER_REPLICATE);
  }
  if (options_.noise_sigma > 0.0) {
    cv::Mat noise(size, CV_32FC3);
    cv::RNG rng(SimHash(options_.seed, kNoiseStream, frame));
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options_.noise_sigma);
    work += noise;
  }
  cv::Mat out;
  work.convertTo(out, CV_8UC3);  // rounds and saturates to [0, 255]
  return out;
}

}  // namespace kapfix
