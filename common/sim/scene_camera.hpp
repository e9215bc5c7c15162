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
  // The field's image disturbances (issue 9), all off by default:
  // [deg] roll of the image about the optical axis, up to ± this (0…30), slowly varying,
  // with a small perspective (keystone) change that grows with it.
  double roll_max_deg = 0;
  // [1] auto-exposure brightness steps: every 125 frames the gain jumps to 1 ± up to this
  // share (0…0.5); the first 125 frames keep gain 1.
  double exposure_step_max = 0;
  // [frames] share of a frame period the shutter is open: the view's motion during the
  // exposure (Capture's `motion_px` × this) smears the frame; 0 = no motion blur (0…1).
  double motion_blur_exposure = 0;
  std::uint32_t seed = 1;

  bool IsValid(std::string* error) const;
};

// [deg] The roll of the image at `frame` for these options (0 unless roll_max_deg > 0): what
// SceneCamera::RollDeg gives, for callers that need the truth without the camera's scene
// (the closed-loop evaluation's slice truth).
double SceneRollDeg(const SceneCameraOptions& options, int frame);

// A camera looking at a large still scene (SPEC §3): each frame is a W×H window of the
// scene centred at the scene centre plus the line of sight. Moving the line of sight by +d
// moves the scene content by −d in the frame.
//
// Per frame, in this order: bilinear sub-pixel crop (border pixels replicated beyond the
// scene; rotated by the roll with its keystone when roll is on), brightness gain
// 1 + A·sin(2πt/P) times the exposure step, motion blur along the view's motion, optional
// Gaussian blur, Gaussian noise seeded by (seed, frame). Capture is const and keeps no state: it
// may be called from several threads, in any frame order, and gives the same image for the same
// arguments.
class SceneCamera {
 public:
  // The scene may be BGR, grey or BGRA, 8 bit; it is copied. Throws std::invalid_argument
  // for an empty scene, another pixel type or options that are not IsValid.
  SceneCamera(const cv::Mat& scene_bgr, SceneCameraOptions options);

  // BGR CV_8UC3 frame of frame_size. `line_of_sight` [px, scene pixels after upscaling] must
  // be finite (std::invalid_argument otherwise).
  // `motion_px`: how far the line of sight moved over the last frame period [px], which
  // smears the frame when motion_blur_exposure > 0.
  cv::Mat Capture(int frame, cv::Point2d line_of_sight, cv::Point2d motion_px = {0, 0}) const;

  // [deg] roll of the image at `frame` (0 unless roll_max_deg > 0).
  double RollDeg(int frame) const { return SceneRollDeg(options_, frame); }
  // [1] auto-exposure gain step at `frame` (1 unless exposure_step_max > 0).
  double ExposureGain(int frame) const;

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
