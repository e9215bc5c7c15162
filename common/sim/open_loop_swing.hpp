#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "common/sim/kite_motion.hpp"
#include "common/sim/scene_camera.hpp"

namespace kapfix {

// The benchmark swing of SPEC §3. The defaults are exactly the spec's open-loop swing:
// 300×300 frames, A = 100 px, T = 40 frames, τ = 400 frames, Y jitter σ = 2 px, noise σ = 3
// grey levels, brightness ±8 % over 400 frames, no gusts, 400 frames.
struct SwingOptions {
  SceneCameraOptions camera;
  KiteMotionOptions motion;
  int frames = 400;

  // Also rejects a swing amplitude beyond the camera's max excursion, whose frames would
  // show replicated border instead of scene.
  bool IsValid(std::string* error) const;

  // The spec's swing for another frame size (e.g. 640×480). The motion stays in pixels
  // (A = 100 px), so a search range of R = 100 px still covers it and results compare with
  // the 300×300 ones; only the frame (and so the scene it needs) grows.
  static SwingOptions ForFrameSize(cv::Size frame_size);
};

// Free swing with the servos off: a scene camera carried by a kite's damped pendulum.
// Stateless after construction; every accessor is a pure function of t.
class OpenLoopSwing {
 public:
  // Throws std::invalid_argument for an empty scene or options that are not IsValid.
  OpenLoopSwing(const cv::Mat& scene_bgr, SwingOptions options);

  int frames() const { return options_.frames; }
  // BGR frame t, 0 ≤ t < frames() (std::out_of_range otherwise).
  cv::Mat Frame(int t) const;
  // [px] line of sight at frame t (any t; before 0 the rest position).
  cv::Point2d LineOfSight(int t) const;
  // [px] where the reference frame's content appears in frame t minus where it was in the
  // reference frame: −(LineOfSight(t) − LineOfSight(reference_frame)). This is the
  // displacement of SPEC §1 a perfect tracker measures.
  cv::Point2d TrueDisplacement(int t, int reference_frame = 0) const;

  const SceneCamera& camera() const { return camera_; }
  const KiteMotion& motion() const { return motion_; }
  const SwingOptions& options() const { return options_; }

 private:
  SwingOptions options_;
  SceneCamera camera_;
  KiteMotion motion_;
};

}  // namespace kapfix
