#include "common/control/swing_predictor.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kapfix {
namespace {

constexpr int kMaxOrder = 32;
constexpr double kOutlierSigmas = 4.0;  // AR residuals beyond this many σ (from MAD) dropped
// [1] total least squares only while the model's weakest direction's singular value is this
// many times the noise floor's (see FitRows): below, the swing is not clear of the noise.
constexpr double kTlsSeparation = 2.0;
// [1] F statistic beyond which the offset's drift is fitted: Akaike's criterion for one more
// unknown (n·ln(RSS₀/RSS₁) > 2). Stricter tests (F > 10) kept out drifts that still spoilt
// the swing's fit; fitting it always cost a steady swing's forecast ~20 %.
constexpr double kDriftSignificance = 2.0;
// [samples] one-step innovations averaged before a jump can be told from the noise.
constexpr int kJumpWarmupSamples = 8;

double Median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// lags: one row per fitted sample, [x_t, x_{t−1}, …, x_{t−p}]; times: each row's t relative
// to the offset's origin. Returns a_1…a_p, c, d (d = 0 unless drifting).
std::optional<std::vector<double>> FitAutoregression(const Eigen::MatrixXd& lags,
                                                     const Eigen::VectorXd& times, bool drifting) {
  const auto p = static_cast<int>(lags.cols()) - 1;
  const Eigen::Index rows = lags.rows();
  // The offset c (and its drift d·t) is exact, not measured: it is eliminated by projecting
  // every column onto what [1, t] cannot explain — centring, and the slope on t when drifting.
  const Eigen::RowVectorXd mean = lags.colwise().mean();
  Eigen::MatrixXd centred = lags.rowwise() - mean;
  const Eigen::VectorXd t = times.array() - times.mean();
  const double tt = t.squaredNorm();
  if (drifting && tt > 0) centred -= t * ((t.transpose() * centred) / tt);
  // Total least squares: every column carries the same white measurement noise, and TLS,
  // unlike least squares, does not shrink the coefficients for it — LS fits a 40-frame swing
  // with pole radius 0.9975 under σ = 2 px as ~0.9 with a period anywhere from 39 to 160
  // frames. TLS needs the swing to stand clear of the noise: the p-th singular value (the
  // weakest direction the model explains) well above the (p+1)-th (the noise floor).
  // Otherwise — white jitter around an offset, a swing buried in noise — least squares,
  // which fits that as the offset.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
  const Eigen::VectorXd& sv = svd.singularValues();
  Eigen::VectorXd a(p);
  bool solved = false;
  if (sv(p) > 0 && sv(p - 1) >= kTlsSeparation * sv(p)) {
    const Eigen::VectorXd v = svd.matrixV().col(p);
    if (std::abs(v(0)) > 1e-9) {
      a = -v.tail(p) / v(0);
      solved = a.allFinite();
    }
  }
  if (!solved) {
    // Below full rank (a constant series, say) there is no unique fit, and no swing to model.
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(centred.rightCols(p));
    qr.setThreshold(1e-9);
    if (rows < p + 1 || qr.rank() < p) return std::nullopt;
    a = qr.solve(centred.col(0));
    if (!a.allFinite()) return std::nullopt;
  }
  // The offset the coefficients leave: c + d·t through the residuals' mean and slope.
  const Eigen::VectorXd residual = lags.col(0) - lags.rightCols(p) * a;
  const double d = drifting && tt > 0 ? t.dot(residual) / tt : 0.0;
  const double c = residual.mean() - d * times.mean();
  std::vector<double> w(a.data(), a.data() + p);
  w.push_back(c);
  w.push_back(d);
  return w;
}

// Each row's x_t − (Σ a_i·x_{t−i} + c + d·t) for coefficients a_1…a_p, c, d.
Eigen::VectorXd EquationResiduals(const Eigen::MatrixXd& lags, const Eigen::VectorXd& times,
                                  const std::vector<double>& w) {
  const auto p = static_cast<int>(lags.cols()) - 1;
  const Eigen::Map<const Eigen::VectorXd> a(w.data(), p);
  return (lags.col(0) - lags.rightCols(p) * a).array() - w[p] - w[p + 1] * times.array();
}

}  // namespace

bool SwingPredictorOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (order < 1 || order > kMaxOrder) {
    return fail("predictor order must be 1…" + std::to_string(kMaxOrder) + ", got " +
                std::to_string(order));
  }
  if (lead_frames < 1 || lead_frames > 1000) {
    return fail("predictor lead must be 1…1000 frames, got " + std::to_string(lead_frames));
  }
  // A robust fit of p + 1 unknowns wants several samples per unknown.
  if (window_frames < 4 * (order + 1) || window_frames > 100000) {
    return fail("predictor window must be 4·(order + 1)…100000 frames, got " +
                std::to_string(window_frames));
  }
  if (!(state_noise_ratio > 0) || !std::isfinite(state_noise_ratio)) {
    return fail("predictor state noise ratio must be finite and > 0");
  }
  if (!(jump_sigmas > 0) || !std::isfinite(jump_sigmas) || !(min_jump >= 0) ||
      !std::isfinite(min_jump)) {
    return fail("predictor jump thresholds must be finite, σ > 0, minimum ≥ 0");
  }
  if (!(max_spectral_radius > 0) || !std::isfinite(max_spectral_radius)) {
    return fail("predictor max spectral radius must be > 0");
  }
  if (!std::isfinite(linear_prior_min_step) || linear_prior_min_step < 0) {
    return fail("predictor linear prior step must be ≥ 0");
  }
  if (skill_frames < 1 || min_skill_samples < 1 || max_coast_frames < 0) {
    return fail("predictor skill span and samples must be ≥ 1, coast frames ≥ 0");
  }
  return true;
}

SwingPredictor::SwingPredictor(SwingPredictorOptions options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("SwingPredictor: " + error);
  Clear();
}

void SwingPredictor::Clear() {
  history_.clear();
  imputed_.clear();
  jumped_.clear();
  filtered_.clear();
  coefficients_.clear();
  newest_time_ = -1;
  offset_origin_ = 0;
  state_.clear();
  chosen_ = Forecaster::kPersistence;
  for (double& s : skill_) s = std::numeric_limits<double>::quiet_NaN();
  innovation_sq_ = 0;
  innovation_samples_ = 0;
  coasted_ = 0;
}

double SwingPredictor::OneStep(const std::vector<double>& state, long long time) const {
  const int p = options_.order;
  double next =
      coefficients_[p] + coefficients_[p + 1] * static_cast<double>(time - offset_origin_);
  for (int i = 0; i < p; ++i) next += coefficients_[i] * state[i];
  return next;
}

double SwingPredictor::ModelForecast(std::vector<double> state, long long time, int frames) const {
  double next = state[0];
  for (int k = 1; k <= frames; ++k) {
    next = OneStep(state, time + k);
    state.pop_back();
    state.insert(state.begin(), next);
  }
  return next;
}

std::optional<double> SwingPredictor::Forecast(int frames) const {
  const int n = samples();
  if (n == 0 || frames < 1) return std::nullopt;
  switch (chosen_) {
    case Forecaster::kModel:
      if (static_cast<int>(state_.size()) != options_.order) break;  // the state fit failed
      return ModelForecast(state_, newest_time_, frames);
    case Forecaster::kLinear:
      if (n < 2) break;
      return history_[n - 1] + frames * (history_[n - 1] - history_[n - 2]);
    case Forecaster::kPersistence:
      break;
  }
  return history_[n - 1];
}

std::optional<double> SwingPredictor::Predict() const {
  if (chosen_ == Forecaster::kPersistence) return std::nullopt;
  return Forecast(options_.lead_frames);
}

double SwingPredictor::skill_rms(Forecaster forecaster) const {
  return skill_[static_cast<int>(forecaster)];
}

void SwingPredictor::Add(double x) {
  if (!std::isfinite(x)) {
    AddMissing();
    return;
  }
  coasted_ = 0;
  Append(x, /*imputed=*/false);
}

bool SwingPredictor::AddMissing() {
  if (chosen_ == Forecaster::kPersistence || coasted_ >= options_.max_coast_frames) {
    Clear();
    return false;
  }
  ++coasted_;
  Append(*Forecast(1), /*imputed=*/true);
  return true;
}

void SwingPredictor::Append(double x, bool imputed) {
  const int p = options_.order;
  // Jump detection on the model's one-step innovation.
  bool jump = false;
  if (!imputed && !coefficients_.empty() && static_cast<int>(state_.size()) == p) {
    const double innovation = x - OneStep(state_, newest_time_ + 1);
    const double rms = std::sqrt(innovation_sq_);
    jump = innovation_samples_ >= kJumpWarmupSamples &&
           std::abs(innovation) > std::max(options_.jump_sigmas * rms, options_.min_jump);
    if (jump) {
      ++jumps_;
    } else {
      const double alpha = 1.0 / std::min(innovation_samples_ + 1, options_.skill_frames);
      innovation_sq_ += alpha * (innovation * innovation - innovation_sq_);
      ++innovation_samples_;
    }
  }

  history_.push_back(x);
  imputed_.push_back(imputed);
  jumped_.push_back(jump);
  ++newest_time_;
  while (static_cast<int>(history_.size()) > options_.window_frames) {
    history_.pop_front();
    imputed_.pop_front();
    jumped_.pop_front();
  }
  // While coasting the coefficients stay: imputed samples are the model's own.
  if (!imputed || coefficients_.empty()) Refit();
  FilterStates();
  // Keep the choice while coasting: the imputed samples would flatter the forecaster that
  // made them.
  if (!imputed) Score();
}

void SwingPredictor::Score() {
  const int n = samples();
  const int p = options_.order;
  const int lead = options_.lead_frames;
  double sum[3] = {0, 0, 0};
  int count[3] = {0, 0, 0};
  for (int t = std::max(0, n - options_.skill_frames); t < n; ++t) {
    const int known = t - lead;  // the newest sample known when forecasting t
    if (known < 0) continue;
    const double x = history_[t];
    const auto add = [&](Forecaster f, double forecast) {
      const double e = x - forecast;
      sum[static_cast<int>(f)] += e * e;
      ++count[static_cast<int>(f)];
    };
    add(Forecaster::kPersistence, history_[known]);
    if (known >= 1) {
      add(Forecaster::kLinear, history_[known] + lead * (history_[known] - history_[known - 1]));
    }
    if (!coefficients_.empty() && known >= p - 1) {
      // The forecast exactly as Forecast() would have made it at `known`: from the filter's
      // state then, which saw only the samples up to `known`.
      const std::vector<double> state = StateAt(known);
      if (!state.empty()) add(Forecaster::kModel, ModelForecast(state, TimeOf(known), lead));
    }
  }
  chosen_ = Forecaster::kPersistence;
  double best = std::numeric_limits<double>::infinity();
  for (const Forecaster f : {Forecaster::kPersistence, Forecaster::kLinear, Forecaster::kModel}) {
    const int i = static_cast<int>(f);
    skill_[i] =
        count[i] > 0 ? std::sqrt(sum[i] / count[i]) : std::numeric_limits<double>::quiet_NaN();
    const bool eligible =
        f == Forecaster::kPersistence ? count[i] > 0 : count[i] >= options_.min_skill_samples;
    if (eligible && skill_[i] < best) {
      best = skill_[i];
      chosen_ = f;
    }
  }
  // Before there is evidence either way, a platform that swings moves smoothly: extrapolate
  // its last step rather than hold (persistence trails a 40-frame swing by ~30 px two frames
  // ahead; the extrapolation by ~3 px) — unless the step is small enough to be jitter.
  const int linear = static_cast<int>(Forecaster::kLinear);
  if (chosen_ == Forecaster::kPersistence && n >= 2 && count[linear] < options_.min_skill_samples &&
      std::abs(history_[n - 1] - history_[n - 2]) >= options_.linear_prior_min_step) {
    chosen_ = Forecaster::kLinear;
  }
  if (chosen_ == Forecaster::kModel && state_.empty()) chosen_ = Forecaster::kPersistence;
}

bool SwingPredictor::Refit() {
  const int p = options_.order;
  const int n = static_cast<int>(history_.size());
  const int rows = n - p;
  coefficients_.clear();
  if (rows < 2 * (p + 1)) return false;
  Eigen::MatrixXd lags(rows, p + 1);
  Eigen::VectorXd times(rows);  // relative to the newest sample, where c is the offset
  for (int r = 0; r < rows; ++r) {
    for (int i = 0; i <= p; ++i) lags(r, i) = history_[r + p - i];
    times(r) = static_cast<double>(r + p - (n - 1));
  }
  // A drifting offset only where it explains more than its cost (an F test on the equation
  // residuals): an extra unknown costs a steady swing's forecast precision. And only over a
  // full window: over the lock-on's first samples a drift is hard to tell from the swing's
  // start (fitted there, a calibration 1.3 × off under latency jitter rang for 100 frames).
  std::optional<std::vector<double>> w = FitAutoregression(lags, times, false);
  Eigen::VectorXd residuals;
  if (w) residuals = EquationResiduals(lags, times, *w);
  bool drifting = false;
  if (options_.drifting_offset && n >= options_.window_frames) {
    if (std::optional<std::vector<double>> wd = FitAutoregression(lags, times, true)) {
      Eigen::VectorXd drift_residuals = EquationResiduals(lags, times, *wd);
      const double drift = drift_residuals.squaredNorm();
      drifting =
          !w || residuals.squaredNorm() - drift > kDriftSignificance * drift / (rows - (p + 2));
      if (drifting) {
        w = std::move(wd);
        residuals = std::move(drift_residuals);
      }
    }
  }
  if (!w) return false;
  // One robust pass: refit without the equation residuals beyond kOutlierSigmas (a gust's
  // innovation, a bad match).
  std::vector<double> abs_res(static_cast<std::size_t>(rows));
  for (int r = 0; r < rows; ++r) abs_res[r] = std::abs(residuals(r));
  const double sigma = 1.4826 * Median(abs_res);
  if (sigma > 0) {
    std::vector<Eigen::Index> keep;
    for (int r = 0; r < rows; ++r) {
      if (abs_res[r] <= kOutlierSigmas * sigma) keep.push_back(r);
    }
    if (static_cast<int>(keep.size()) < rows && static_cast<int>(keep.size()) >= 2 * (p + 1)) {
      if (auto w2 = FitAutoregression(lags(keep, Eigen::all), times(keep), drifting)) {
        w = std::move(w2);
      }
    }
  }
  // Reject fits that would grow without bound: the companion matrix's spectral radius.
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(p, p);
  for (int i = 0; i < p; ++i) companion(0, i) = (*w)[i];
  for (int i = 1; i < p; ++i) companion(i, i - 1) = 1.0;
  const double radius = companion.eigenvalues().cwiseAbs().maxCoeff();
  if (!(radius <= options_.max_spectral_radius)) return false;
  coefficients_ = std::move(*w);
  offset_origin_ = newest_time_;
  return true;
}

void SwingPredictor::FilterStates() {
  const int p = options_.order;
  const int n = samples();
  filtered_.clear();
  state_.clear();
  if (coefficients_.empty() || n < p) return;
  // The state s_k = [x_k … x_{k−p+1}] moves as s_k = F·s_{k−1} + (c + d·t_k + w_k)·e₁, with
  // w the swing's push off the model (variance q) and each sample x_k + v_k (variance r).
  // Only q/r matters for the filtered state, so r = 1. It starts from the first p samples
  // as measured (covariance r·I).
  const double q = options_.state_noise_ratio;
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(p, p);
  for (int i = 0; i < p; ++i) f(0, i) = coefficients_[i];
  for (int i = 1; i < p; ++i) f(i, i - 1) = 1.0;
  Eigen::VectorXd s(p);
  for (int i = 0; i < p; ++i) s(i) = history_[p - 1 - i];
  Eigen::MatrixXd cov = Eigen::MatrixXd::Identity(p, p);
  filtered_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(p),
                   std::numeric_limits<double>::quiet_NaN());
  const auto store = [&](int k) {
    for (int i = 0; i < p; ++i)
      filtered_[(static_cast<std::size_t>(k) * static_cast<std::size_t>(p)) +
                static_cast<std::size_t>(i)] = s(i);
  };
  store(p - 1);
  // Buffers kept across the window's samples: the filter runs over the whole window after
  // every sample, on both axes.
  Eigen::VectorXd predicted(p);
  Eigen::VectorXd gain(p);
  Eigen::MatrixXd product(p, p);
  for (int k = p; k < n; ++k) {
    const double forced =
        coefficients_[p] + coefficients_[p + 1] * static_cast<double>(TimeOf(k) - offset_origin_);
    predicted.noalias() = f * s;
    s = predicted;
    s(0) += forced;
    product.noalias() = f * cov;
    cov.noalias() = product * f.transpose();
    cov(0, 0) += q;
    if (jumped_[k]) {
      // A gust broke the recurrence at this sample: its value is the sample itself, known
      // only to the measurement's noise; the older values keep what they were.
      s(0) = history_[k];
      cov.row(0).setZero();
      cov.col(0).setZero();
      cov(0, 0) = 1.0;
    } else if (!imputed_[k]) {
      const double innovation = history_[k] - s(0);
      gain = cov.col(0) / (cov(0, 0) + 1.0);
      s += gain * innovation;
      product.noalias() = gain * cov.row(0);
      cov -= product;
    }
    if (!s.allFinite()) {
      filtered_.clear();
      return;
    }
    store(k);
  }
  state_ = StateAt(n - 1);
}

std::vector<double> SwingPredictor::StateAt(int newest) const {
  const int p = options_.order;
  if (filtered_.empty() || newest < p - 1) return {};
  const auto first =
      filtered_.begin() + (static_cast<std::ptrdiff_t>(newest) * static_cast<std::ptrdiff_t>(p));
  return {first, first + p};
}

}  // namespace kapfix
