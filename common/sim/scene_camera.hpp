#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

namespace kapfix {

struct SceneCameraOptions {
  cv::Size frame_size{300, 300};          // W×H [px] of a captured frame
  double noise_sigma = 3.0;               // [grey levels] Gaussian sensor noise per pixel
  double brightness_amplitude = 0.08;     // gain 1 ± this (±8 %), in [0, 1)
  double brightness_period_frames = 400;  // [frames] period of the brightness drift
  double blur_sigma = 0.0;                // [px] optional Gaussian blur, 0 = off
  // [px] how far the line of sight may go from the scene centre with the window still
  // inside the scene; a smaller scene is upscaled to cover frame + 2·this.
  double max_excursion_px = 130;
  std::uint32_t seed = 1;

  bool IsValid(std::string* error) const;
};

// A camera looking at a large still scene (SPEC §3): each frame is a W×H window of the
// scene centred at the scene centre plus the line of sight. Moving the line of sight by +d
// moves the scene content by −d in the frame.
//
// Per frame, in this order: bilinear sub-pixel crop (border pixels replicated beyond the
// scene), brightness gain 1 + A·sin(2πt/P), optional blur, Gaussian noise seeded by
// (seed, frame). Capture is const and keeps no state: it may be called from several
// threads, in any frame order, and gives the same image for the same arguments.
class SceneCamera {
 public:
  // The scene may be BGR, grey or BGRA, 8 bit; it is copied. Throws std::invalid_argument
  // for an empty scene, another pixel type or options that are not IsValid.
  SceneCamera(const cv::Mat& scene_bgr, SceneCameraOptions options);

  // BGR CV_8UC3 frame of frame_size. `line_of_sight` [px, scene pixels after upscaling] must
  // be finite (std::invalid_argument otherwise).
  cv::Mat Capture(int frame, cv::Point2d line_of_sight) const;

  // Brightness gain applied at `frame`: 1 + brightness_amplitude·sin(2π·frame/period).
  double BrightnessGain(int frame) const;
  // 1 when the scene already covered frame + 2·max_excursion; the factor it was enlarged
  // by otherwise — callers print it, since an
  // upscaled scene carries less detail per pixel.
  double upscale_factor() const { return upscale_factor_; }
  // [px] size of the scene the camera crops from, after upscaling.
  cv::Size scene_size() const { return scene_.size(); }
  const SceneCameraOptions& options() const { return options_; }

 private:
  SceneCameraOptions options_;
  cv::Mat scene_;  // BGR CV_8UC3, upscaled if needed
  double upscale_factor_ = 1.0;
};

}  // namespace kapfix
