#pragma once

#include <deque>
#include <string>

namespace kapfix {

struct DegPerPxEstimatorOptions {
  int window_frames = 250;  // [frames] recent frames the estimate is fitted on
  // [1] AR order of the swing model: 2 is a damped pendulum; more absorbs coloured
  // turbulence on top of it, which an AR(2) would partly blame on the servo.
  int order = 2;
  int min_samples = 12;  // [frames] fitted rows before the estimate may be trusted
  int refit_every = 5;   // [frames] between fits
  // [1] the estimate is trusted once its relative standard deviation is below this.
  double max_relative_sigma = 0.035;
  // [1] the search spans [1/this, this] × the starting calibration: a lens is never off by
  // more, and a fit on a degenerate stretch must not run away.
  double max_ratio = 2.5;

  bool IsValid(std::string* error) const;
};

// Estimates one axis's degrees per pixel from the loop's own commands and the measured
// response, while it flies (issue 9, "a loop that knows its calibration").
//
// The view the servo corrects is u = angle / deg_per_px + displacement: the platform's own
// swing [px], which does not depend on what the servo did. With a wrong deg per px, u carries
// a share of the servo's motion, whose steps (the loop's corrections, delayed by its
// latency) the swing's smooth dynamics cannot explain. So the estimate is the θ = 1/deg_per_px
// [px/deg] for which u_θ = displacement + θ·angle is best explained by a damped pendulum
// around an offset, u_t = α1·u_{t−1} + α2·u_{t−2} + c (AR(2), least squares for each θ): the
// residual sum of squares over the window is minimised over log θ (a grid, then a parabola
// through the best three points). Measurement noise that the angle does not carry adds the
// same to every θ's residual and does not bias the minimum. Known limit (not finished): in
// closed loop the angle carries the noise of the frames it was computed from, so a θ off the
// truth can cancel part of that noise; at the simulated matcher's 0.1–0.2 px the estimate
// ends within 2 %, but a noisier matcher would bias it (an instrumental-variable fit would
// remove that; a recursive IV ARX tried first needed far more excitation than a well-held
// loop gives). The uncertainty comes from the curvature of that residual
// (σ² = 2·s² / RSS''), so a stretch where the servo moved only with the swing — which any θ
// explains — shows as a flat residual and a large σ: the estimate is trusted only after
// min_samples rows and while σ_θ/θ is below max_relative_sigma.
class DegPerPxEstimator {
 public:
  // `start_deg_per_px`: the stored calibration or the lens's optics (finite, non-zero).
  // Throws std::invalid_argument for a bad start or options that are not IsValid.
  DegPerPxEstimator(double start_deg_per_px, DegPerPxEstimatorOptions options = {});

  // One frame: the angle the frame was seen through [deg] and its measured displacement [px].
  void Add(double angle_deg, double displacement_px);
  void AddMissing();  // no measurement this frame (breaks the rows that span it)
  // Back to the start, forgetting the frames (a new stored calibration).
  void Restart(double start_deg_per_px);

  double estimate_deg_per_px() const { return estimate_deg_per_px_; }  // [deg/px]
  double relative_sigma() const { return relative_sigma_; }  // [1] σ_θ/θ; +∞ before a fit
  bool trusted() const;
  int samples() const { return rows_; }  // [frames] rows of the last fit

 private:
  struct Sample {
    double angle_deg, displacement_px;
    bool valid;
  };
  // The AR(2) residual sum of squares of u_θ over the window; *rows: rows used.
  double ResidualSumOfSquares(double theta, int* rows) const;
  void Fit();

  DegPerPxEstimatorOptions options_;
  double start_deg_per_px_ = 0;
  double estimate_deg_per_px_ = 0;
  double relative_sigma_ = 0;
  std::deque<Sample> window_;  // oldest first
  int rows_ = 0;
  int since_fit_ = 0;
};

}  // namespace kapfix
