#pragma once

#include <Eigen/Core>
#include <deque>
#include <string>
#include <vector>

namespace kapfix {

struct DegPerPxEstimatorOptions {
  // [frames] recent frames the estimate is fitted on (whole segments): the lens does not
  // change in flight, so a long memory keeps the lock-on's and the gusts' information.
  int window_frames = 1000;
  // [1] AR order of the swing model: 2 is a damped pendulum; more absorbs coloured
  // turbulence on top of it, which an AR(2) would partly blame on the servo.
  int order = 2;
  // [frames] fitted rows before the estimate may be trusted; σ is widened by Student's t for
  // the few rows beyond the parameters, so a dozen rows are trusted only when they agree.
  int min_samples = 10;
  // [frames] between fits, once the estimate was first trusted; before that every frame is
  // fitted (for up to 60 frames), since on lock-on each frame on a wrong calibration costs
  // most (calibration ×0.6 from the first frame: 5.2 → 4.1 px median).
  int refit_every = 5;
  // [1] the estimate is trusted once its relative standard deviation is below this.
  double max_relative_sigma = 0.035;
  // [1] the search spans [1/this, this] × the starting calibration: a lens is never off by
  // more, and a fit on a degenerate stretch must not run away.
  double max_ratio = 2.5;
  // [frames] the window is fitted in segments of this length, each with its own swing model
  // (the period and damping may wander) but one deg/px for all.
  int segment_frames = 50;
  // Fit the servo's play: the output lags the command by half the backlash in the direction
  // it last moved (a hobby servo's gears), which a closed loop holding the view would
  // otherwise blame on the calibration.
  bool backlash = true;
  // [1] a segment joins the fit only if its own residual curve has a minimum within the span
  // with σ_θ/θ below this: a segment in which the servo only followed the swing carries no
  // information on θ, only a slope of its measurement noise.
  double segment_max_relative_sigma = 0.3;

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
// through the best three points).
//
// The servo's play. The angle the loop knows is the one it commanded; a hobby servo's output
// lags it by half its backlash in the direction it last moved. Once the loop holds the view,
// that lag (~0.5 px at 0.1° of play) is as large as what is left of the servo's own moves,
// and an AR(2) cannot explain its square wave: the fit leaned on θ to cancel it and ended
// 5–27 % off (the same frames with the servo's true output angles: within 1 %). So each row
// also carries the direction the angle last moved, at each lag, with free coefficients.
//
// Where the information is. The window is split into segments of segment_frames, each with
// its own swing model (AR coefficients, offset, play), but one θ for all: the residual curves
// of the segments are added and minimised together. A segment in which the servo only
// followed the swing (a well-held view) pins θ down no better than segment_max_relative_sigma
// and is left out: its curve carries only the slope its measurement noise gives the residual
// (the swing is in the angle, scaled by θ, the noise is not), which over a long hold carried
// the estimate off. So the estimate stays where the lock-on's and the gusts' corrections put
// it. Rows whose residual is far beyond their segment's median are not fitted (a frame seen
// through another command than the loop believes, a false match).
//
// Known limit (not finished): the angle must be the one the frame was seen through. Under
// latency jitter with a wrong calibration the loop's belief of it (ServoBelief) is wrong on
// most lock-on frames, and so is the estimate (realistic world: 0.92–1.37, untrusted; with the
// true angles within 1 %).
//
// Known limit: in closed loop the angle carries the noise of the frames it was
// computed from, so a θ off the truth can cancel part of that noise; at the simulated
// matcher's 0.1–0.2 px the estimate ends within 2 %, but a noisier matcher would bias it (an
// instrumental-variable fit would remove that; a recursive IV ARX tried first needed far more
// excitation than a well-held loop gives). The uncertainty comes from the curvature of the
// summed residual (σ² = 2·s² / RSS''), so a stretch where the servo moved only with the swing
// — which any θ explains — shows as a flat residual and a large σ: the estimate is trusted
// only after min_samples rows and while σ_θ/θ is below max_relative_sigma.
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
  bool ever_trusted() const { return ever_trusted_; }  // since the (re)start
  int samples() const { return rows_; }                // [frames] rows of the last fit

 private:
  struct Sample {
    double angle_deg, displacement_px;
    bool valid;
    double direction;  // [1] +1 / −1: the way the angle last moved (0 before it moved)
  };
  // The sums of z·zᵀ over a segment's rows, z = (d_t…d_{t−p}, a_t…a_{t−p}, 1, s_t…s_{t−p}):
  // all a segment's residual curve needs.
  struct Segment {
    Eigen::MatrixXd sums;
    int rows = 0;
    int frames = 0;
  };
  int RowSize() const;  // size of z
  void AddRow();        // the row ending at the newest sample, if its frames are all measured
  void CloseSegment();
  double GridTheta(int i) const;                  // [px/deg] the i-th θ candidate
  double GridStep() const;                        // [1] of log θ between candidates
  Eigen::MatrixXd Transform(double theta) const;  // z → (u_t…u_{t−p}, 1, s_t…s_{t−p})
  // The swing model's residual sum of squares at θ over a segment (NaN: too few rows), and
  // its coefficients (α…, c, γ…).
  double SwingModel(const Segment& segment, double theta, Eigen::VectorXd* coefficients) const;
  std::vector<double> Curve(const Segment& segment) const;  // SwingModel's RSS over the grid
  // The segment of `rows` without its outlying rows.
  Segment Screened(const std::vector<Eigen::VectorXd>& rows, int frames) const;
  void Fit();

  DegPerPxEstimatorOptions options_;
  double start_deg_per_px_ = 0;
  double estimate_deg_per_px_ = 0;
  double relative_sigma_ = 0;
  std::deque<Sample> recent_;               // the last order + 1 samples, oldest first
  std::deque<Segment> closed_;              // oldest first, within window_frames with the open one
  std::vector<Eigen::VectorXd> open_rows_;  // z of the open segment's rows
  int open_frames_ = 0;
  double last_angle_deg_ = 0;
  bool moved_ = false;  // an angle has been seen (direction_ is meaningful after a change)
  double direction_ = 0;
  int rows_ = 0;
  int since_fit_ = 0;
  int lock_on_frames_ = 0;  // [frames] measured since the (re)start, counted to kLockOnFrames
  bool ever_trusted_ = false;
};

}  // namespace kapfix
