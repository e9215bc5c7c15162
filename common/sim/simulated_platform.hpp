#pragma once

#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>

#include "common/sim/boat_motion.hpp"
#include "common/sim/kite_motion.hpp"
#include "common/sim/platform_motion.hpp"
#include "common/sim/scene_camera.hpp"
#include "common/sim/simulated_servo.hpp"

namespace kapfix {

struct SimulatedPlatformOptions {
  enum class Motion { kKite, kBoat };
  Motion motion = Motion::kKite;
  KiteMotionOptions kite;  // used when motion is kKite
  BoatMotionOptions boat;  // used when motion is kBoat
  SceneCameraOptions camera;
  SimulatedServoOptions pan;   // turns the line of sight along x
  SimulatedServoOptions tilt;  // turns the line of sight along y
  double px_per_deg = 10.0;    // [px/deg] lens: scene pixels the view moves per degree of servo
  // [1] share of frames the camera loses (0…0.5), decided per frame from the camera's seed;
  // see FrameDropped.
  double frame_drop_rate = 0;

  bool IsValid(std::string* error) const;
};

// One captured frame with what it was seen through, read atomically.
struct SimulatedFrame {
  cv::Mat image;        // BGR CV_8UC3
  int frame = 0;        // index of the frame
  double pan_deg = 0;   // [deg] pan output angle while the frame was exposed
  double tilt_deg = 0;  // [deg] tilt output angle while the frame was exposed
};

// The closed-loop world of SPEC §3: a scene camera carried by a swinging platform (kite or
// boat) and pointed by two simulated servos.
//
// Sign chain, end to end (tested in simulated_platform_test and fixation_loop_test):
//   line of sight [px] = motion(t) + (pan, tilt) [deg] · px_per_deg,
// so a positive pan turns the view right (+x) and a positive tilt down (+y), like the motion.
// The scene content then moves the opposite way in the frame, so the displacement measured
// against a stored reference (SPEC §1) is −(line of sight − the reference's line of sight).
// A positive measured displacement therefore means the view went left/up, and a positive
// servo command brings it back: the controller's calibration (LensCalibration, deg per px)
// is +1/px_per_deg and target = angle + displacement · deg_per_px. (A thesis-style
// calibration, which measures the displacement a move *causes*, finds −1/px_per_deg: see
// LensCalibration::FromCalibrationMoves.)
//
// Thread-safe: one mutex guards the frame index and the servos, so a capture thread may call
// Capture/Step while a control thread calls Command*. Rendering happens outside the lock.
class SimulatedPlatform {
 public:
  // Throws std::invalid_argument for an empty scene or options that are not IsValid.
  SimulatedPlatform(const cv::Mat& scene_bgr, SimulatedPlatformOptions options);

  // The frame at the current frame index: line of sight = motion(frame) + servo output
  // angles · px_per_deg.
  cv::Mat Capture() const;
  // The same, with the frame index and the servo angles it was seen through.
  SimulatedFrame CaptureFrame() const;

  // Queue a servo target [deg]; the servo's latency, rate limit, dead band, backlash and hard
  // limits apply (SimulatedServo). NaN is ignored.
  void CommandPan(double deg);
  void CommandTilt(double deg);

  // Advances one frame: each servo steps once, then the frame index grows by one. With
  // latency 0 a command sent after capturing frame t shows in frame t + 1; with latency L in
  // frame t + 1 + L.
  void Step();

  // Whether the camera loses frame `frame` (the platform still moves; nobody sees it).
  // A pure function of (camera seed, frame).
  bool FrameDropped(int frame) const;

  int frame() const;
  // [px] current line of sight (motion plus servos), scene pixels.
  cv::Point2d LineOfSight() const;
  // [px] residual offset of the view from frame 0's view: line of sight now − line of sight
  // at frame 0 (with the servos at their initial angles). Perfect stabilisation keeps it at
  // 0; the content appears displaced by −ViewOffset() against frame 0.
  cv::Point2d ViewOffset() const;
  // [px] where the motion alone (servos still at their initial angles) would put the view,
  // relative to frame 0's view: the open-loop swing.
  cv::Point2d OpenLoopOffset() const;
  double pan_deg() const;   // [deg] pan output angle
  double tilt_deg() const;  // [deg] tilt output angle

  const SimulatedPlatformOptions& options() const { return options_; }
  double upscale_factor() const { return camera_.upscale_factor(); }

 private:
  cv::Point2d LineOfSightLocked() const;

  const SimulatedPlatformOptions options_;
  const SceneCamera camera_;
  const std::unique_ptr<const PlatformMotion> motion_;
  cv::Point2d initial_line_of_sight_;

  mutable std::mutex mutex_;
  SimulatedServo pan_;
  SimulatedServo tilt_;
  int frame_ = 0;
  cv::Point2d previous_line_of_sight_;  // [px] at the previous frame, for motion blur
};

}  // namespace kapfix
