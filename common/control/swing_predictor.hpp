#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace kapfix {

struct SwingPredictorOptions {
  // [1] autoregressive order p. A kite's damped pendulum (with same-period gusts) is exactly
  // AR(2) plus an offset; a boat's roll with superposed waves needs more.
  int order = 2;
  int lead_frames = 2;     // [frames] how far ahead Predict() looks
  int window_frames = 80;  // [frames] history the model's coefficients are fitted on
  // [1] the state filter's ratio of process to measurement noise: the variance of what
  // pushes the swing off the model each frame (wind on the rig, a sway the drift does not
  // follow) over that of the measurement. Smaller trusts the model longer and averages more
  // noise; larger follows the samples. At 1 a realistic world's recorded views (broadband
  // wind, sway, 0.6–1.1 px of noise) were forecast 2–3 frames ahead with 2.2 px RMS, against
  // 3.4 px for a state fitted through the model to the last 8 samples (no process noise);
  // 0.1 and 3 gave 2.7 and 2.1.
  double state_noise_ratio = 1.0;
  // A one-step innovation beyond jump_sigmas · its running RMS (and beyond min_jump) is a
  // jump — a gust, say — and restarts the state filter's newest value at that sample.
  double jump_sigmas = 4.0;
  double min_jump = 1.0;  // [units of the samples, px in the controller]
  // Fits whose companion matrix has a larger spectral radius grow without bound: rejected.
  double max_spectral_radius = 1.05;
  // [frames] how many recent samples each forecaster is scored on (see SwingPredictor).
  int skill_frames = 20;
  // The model is used only once it has been scored on at least this many samples; linear
  // is used until it has been scored on this many and found worse than persistence.
  int min_skill_samples = 3;
  // [units] the linear forecaster is preferred before it has been scored only after a step
  // at least this large: a kite swing moves up to ~16 px per frame, while SPEC §3's jitter
  // (σ = 2 px, so σ = 2.8 px per step) stays below 8 px in 99.6 % of steps, and
  // extrapolating jitter would amplify it.
  double linear_prior_min_step = 8.0;
  int max_coast_frames = 3;  // [frames] missing samples bridged by the model's own forecast
  // The model's offset may drift linearly over the window (x_n = Σ a_i·x_{n−i} + c + d·n),
  // fitted over a full window where it explains more than its cost (Akaike's criterion): a
  // slow sway of the line under the swing moves the level the swing is around. Without it
  // that drift is fitted as part of the swing — an AR(2) of a 40-frame swing under a 20 px
  // sway of 7 swing periods forecast 2 frames ahead with 2.5 px RMS instead of 0.5, and
  // white jitter under a slow sway was forecast worse than persistence.
  bool drifting_offset = true;

  bool IsValid(std::string* error) const;
};

// Forecasts a scalar series sampled once per frame — the line of sight of a swinging
// platform — lead_frames ahead (SPEC §3: the view is seen one frame late and the servo adds
// its latency, so a controller must act on where the swing will be, not where it was).
//
// Three forecasters compete:
//  - persistence: "it stays where it is" — what a plain proportional controller acts on;
//  - linear: the last step extrapolated (x_n + lead·(x_n − x_{n−1})), which carries the loop
//    while the model has too few samples; until it has been scored it is preferred to
//    persistence after a large step (a swinging platform moves smoothly);
//  - model: x_n = a_1·x_{n−1} + … + a_p·x_{n−p} + c + d·n (d: the offset's drift, see
//    SwingPredictorOptions::drifting_offset), fitted over the window by total least
//    squares (unbiased under white measurement noise, where least squares shrinks the
//    poles: a 40-frame swing of pole radius 0.9975 under σ = 2 px came out ~0.9 with periods
//    wandering from 39 to hundreds of frames) — least squares only where no swing stands
//    clear of the noise — refitted after every sample with one robust pass (residuals beyond
//    4σ of their MAD dropped, so a gust's single innovation does not bend the fit). A damped
//    sinusoid around an offset satisfies AR(2) exactly, whatever its amplitude and phase,
//    and a gust of the same period breaks the recurrence for one sample only; white jitter
//    around an offset fits as that offset. The forecast starts from the state (the last p
//    values) estimated by a Kalman filter run over the window with the model: it averages
//    the measurement noise the recurrence would otherwise amplify (×3.5 for a 40-frame period
//    two frames ahead), and, unlike a state fitted through the model as if nothing pushed
//    the swing, it lets wind move the swing off the model between samples
//    (state_noise_ratio); a jump restarts the filter's newest value at that sample.
// After every sample each forecaster is scored on the last skill_frames samples, forecasting
// each from what was known lead_frames before it exactly as Forecast() would have then (the
// model with its current coefficients, from the filter's state at that sample, which saw
// only the samples up to it: the forecast it acts on, not one from raw samples). Predict()
// returns the best one's forecast, or nothing — the caller falls back to plain P — while
// persistence is best.
class SwingPredictor {
 public:
  enum class Forecaster { kPersistence, kLinear, kModel };

  // Throws std::invalid_argument for options that are not IsValid.
  explicit SwingPredictor(SwingPredictorOptions options = {});

  // The newest sample (one per frame, in order). Non-finite samples count as missing.
  void Add(double x);
  // No sample this frame: bridged with the chosen forecaster's one-step forecast for up to
  // max_coast_frames in a row while that is not persistence. Returns false, and forgets
  // everything, otherwise.
  bool AddMissing();
  void Clear();

  // The forecast lead_frames after the newest sample, unless persistence is the best.
  std::optional<double> Predict() const;
  // The chosen forecaster's forecast `frames` (≥ 1) after the newest sample; the newest
  // sample itself for persistence; nothing without samples.
  std::optional<double> Forecast(int frames) const;
  Forecaster chosen() const { return chosen_; }

  int samples() const { return static_cast<int>(history_.size()); }
  bool has_model() const { return !coefficients_.empty(); }
  // [units] RMS error of a forecaster over its last scoring; NaN when it was not scored.
  double skill_rms(Forecaster forecaster) const;
  int jumps() const { return jumps_; }  // jumps detected since construction
  // a_1…a_p, c, d; c is the offset at the newest sample of the last refit, d its drift
  // [units/frame] (0 without drifting_offset).
  const std::vector<double>& coefficients() const { return coefficients_; }
  const SwingPredictorOptions& options() const { return options_; }

 private:
  void Append(double x, bool imputed);
  bool Refit();
  // Runs the Kalman filter over the window with the current model: filtered_ and state_.
  void FilterStates();
  // The filtered state at index `newest` (the last p values, newest first); empty without a
  // model or before the p-th sample.
  std::vector<double> StateAt(int newest) const;
  void Score();
  // The model's value at sample `time` from the p values before it (newest first).
  double OneStep(const std::vector<double>& state, long long time) const;
  // `frames` after the state, whose newest value is at sample `time`.
  double ModelForecast(std::vector<double> state, long long time, int frames) const;
  // The sample number of history_[index] (sample numbers count every Append since Clear).
  long long TimeOf(int index) const { return newest_time_ - (samples() - 1 - index); }

  SwingPredictorOptions options_;
  std::deque<double> history_;        // oldest first, at most window_frames
  std::deque<bool> imputed_;          // per sample: the model's own forecast (not measured)
  std::deque<bool> jumped_;           // per sample: a jump was detected at it
  std::vector<double> coefficients_;  // a_1…a_p, c, d; empty when there is no model
  long long newest_time_ = -1;        // sample number of the newest sample
  long long offset_origin_ = 0;       // the sample number c is the offset at
  std::vector<double> filtered_;      // per index, its filtered state: p values, newest first
  std::vector<double> state_;         // the newest filtered state, newest first
  Forecaster chosen_ = Forecaster::kPersistence;
  double skill_[3] = {0, 0, 0};  // RMS per Forecaster, NaN when not scored
  double innovation_sq_ = 0;     // running mean squared one-step innovation of the model
  int innovation_samples_ = 0;
  int coasted_ = 0;  // missing samples bridged in a row
  int jumps_ = 0;
};

}  // namespace kapfix
