#include "common/control/servo_belief.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace kapfix {
namespace {

constexpr int kMaxDelayFrames = 1000;
// [frames] a view older than this no longer says where the swing is now: the extrapolation
// restarts from the next measured frame.
constexpr std::int64_t kMaxViewGapFrames = 3;
constexpr std::size_t kViews = 6;     // views the extrapolation is fitted to
constexpr double kMinSpreadPx = 1;    // [px] floor of the views' expected miss
constexpr double kSpreadRate = 0.05;  // [1/frame] EMA rate of the squared miss
// Hypotheses of the commands in effect kept per axis. Replayed offline on a realistic
// flight's commands and measurements, 2 to 32 resolved the servo equally well (0.68 px RMS
// over frames 40–150 of seed 3's fast swing); 1, a hard choice each frame, 0.78.
constexpr std::size_t kPaths = 4;
// The calibration scales the views are scored under: 2^(k/12), k = −12…12 (×0.5…2, the
// calibration-error flag's range, in steps of 6 %: a view reconstructed 3 % off keeps 3 % of
// the servo's steps, well under the candidates' parting), the given calibration's 1 first.
constexpr int kScaleSteps = 12;
constexpr int kMinScaleFrames = 3;  // [frames] scored before another scale may be used
// Another scale is used only once its views miss by less than this share of the one in use's
// (squared px, EMA at kSpreadRate): a margin against flipping between neighbours. It is
// small and kMinScaleFrames short because the lock-on decides the flight: a belief still on
// the calibration ×1.3 over the first ~10 frames let the pull-in ring (40–80 px) and hand the
// axis to P for 100 frames (measured: aero1 realistic seed 2, 13.9 px with 15 frames and a
// 0.7 margin, 7.0 px with these).
constexpr double kScaleMargin = 0.9;
// An axis's views tell the scales apart where their miss grows clearly away from the best
// scale: its sharpness, the grid's worst over best miss (squared px) less 1, at least this.
// Realistic world, aero1.jpg, 10 seeds, scored over whole flights with the servos' true
// angles: pan's was 10–30; tilt's, under a swing of 6–8 px SD that is mostly unforecastable
// sway and jitter, 0.02–0.3, with its best scale at the grid's end (the servo follows
// forecasts of the views' noise, so a larger scale cancels some of it): tilt flew at 0.65 ×
// the true deg/px. Over the belief's ~20-frame memory tilt's still reached 1 at times.
constexpr double kMinSharpness = 1.0;
// An axis keeps a scale of its own only while it is at least this share of the other's
// sharpness; a duller one takes the sharper axis's scale (both look through one lens).
constexpr double kOwnSharpnessShare = 0.25;

const ServoBeliefOptions& Validated(const ServoBeliefOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("ServoBelief: " + error);
  return options;
}

double Of(const ServoTargets& targets, int axis) {
  return axis == 0 ? targets.pan_deg : targets.tilt_deg;
}

}  // namespace

std::vector<double> DelayShares(int spread) {
  std::vector<double> shares;
  double none_before = 1;  // P(no newer command has arrived)
  for (int k = 0; k <= spread; ++k) {
    const double late = static_cast<double>(spread - k) / (spread + 1);  // P(delay > k)
    shares.push_back(none_before * (1 - late));
    none_before *= late;
  }
  return shares;
}

bool ServoBeliefOptions::IsValid(std::string* error) const {
  if (min_delay_frames < 1 || max_delay_frames < min_delay_frames ||
      max_delay_frames > kMaxDelayFrames) {
    if (error) {
      *error = "servo delay must be 1 ≤ min ≤ max ≤ " + std::to_string(kMaxDelayFrames) +
               " frames, got " + std::to_string(min_delay_frames) + "…" +
               std::to_string(max_delay_frames);
    }
    return false;
  }
  if (!std::isfinite(initial.pan_deg) || !std::isfinite(initial.tilt_deg)) {
    if (error) *error = "servo initial angles must be finite";
    return false;
  }
  if (!(max_step_deg.pan_deg > 0) || !(max_step_deg.tilt_deg > 0)) {
    if (error) {
      *error = "servo speed must be > 0 deg/frame, got " + std::to_string(max_step_deg.pan_deg) +
               " (pan), " + std::to_string(max_step_deg.tilt_deg) + " (tilt)";
    }
    return false;
  }
  if (!(play_deg.pan_deg >= 0 && play_deg.pan_deg <= kMaxServoPlayDeg) ||
      !(play_deg.tilt_deg >= 0 && play_deg.tilt_deg <= kMaxServoPlayDeg)) {
    if (error) {
      *error = "servo play must be 0…" + std::to_string(static_cast<int>(kMaxServoPlayDeg)) +
               " deg, got " + std::to_string(play_deg.pan_deg) + " (pan), " +
               std::to_string(play_deg.tilt_deg) + " (tilt)";
    }
    return false;
  }
  return true;
}

ServoBelief::ServoBelief(ServoBeliefOptions options)
    : options_(Validated(options)),
      shares_(DelayShares(options_.max_delay_frames - options_.min_delay_frames)) {
  scales_.push_back(1.0);
  for (int k = -kScaleSteps; k <= kScaleSteps; ++k) {
    if (k != 0) scales_.push_back(std::exp2(static_cast<double>(k) / kScaleSteps));
  }
  for (int axis = 0; axis < 2; ++axis) {
    axes_[static_cast<std::size_t>(axis)].scale_miss_sq.assign(scales_.size(), 0.0);
    FillCandidates(axis);
  }
}

void ServoBelief::Sent(std::int64_t frame, const ServoTargets& command) {
  sent_.push_back({frame, next_order_++, command});
  // Keep what the longest delay can still reach, plus the command before it.
  while (sent_.size() > 2 && sent_[1].frame <= frame - options_.max_delay_frames) {
    sent_.pop_front();
  }
}

void ServoBelief::FillCandidates(int axis) {
  Axis& a = axes_[static_cast<std::size_t>(axis)];
  a.candidates.clear();
  for (int k = options_.min_delay_frames; k <= options_.max_delay_frames; ++k) {
    const double prior = shares_[static_cast<std::size_t>(k - options_.min_delay_frames)];
    Candidate c{-1, Of(options_.initial, axis), prior};
    for (auto it = sent_.rbegin(); it != sent_.rend(); ++it) {
      if (it->frame <= exposed_ - k) {
        c = {it->order, Of(it->targets, axis), prior};
        break;
      }
    }
    const auto known = std::find_if(a.candidates.begin(), a.candidates.end(),
                                    [&c](const Candidate& o) { return o.order == c.order; });
    if (known == a.candidates.end()) {
      a.candidates.push_back(c);
    } else {
      known->prior += prior;
    }
  }
}

namespace {

// The servo follows the newest pulse it has seen: never a command older than one already in
// effect (unless nothing else is left, e.g. the history was cut).
template <typename Candidate>
std::vector<Candidate> InEffectOrNewer(const std::vector<Candidate>& candidates,
                                       std::int64_t in_effect) {
  std::vector<Candidate> newer;
  for (const Candidate& c : candidates) {
    if (c.order >= in_effect) newer.push_back(c);
  }
  return newer.empty() ? candidates : newer;
}

}  // namespace

ServoBelief::Pose ServoBelief::Reached(const std::deque<View>& views, double max_step_deg,
                                       double play_deg, double command_deg) const {
  if (views.empty()) return {command_deg, command_deg};
  const View& last = views.back();
  const double step = max_step_deg * static_cast<double>(exposed_ - last.frame);
  const double shaft = last.shaft_deg + std::clamp(command_deg - last.shaft_deg, -step, step);
  // The play: the output moves only when the shaft pushes against one side of the gap. Taken
  // as the shaft, the belief was half the play off on almost every frame (0.5 px at the
  // simulated servo's 0.1° and 10 px/deg), the largest noise in the pan views it rebuilt.
  return {std::clamp(last.deg, shaft - play_deg / 2, shaft + play_deg / 2), shaft};
}

double ServoBelief::Expected(int axis) const {
  const Axis& a = axes_[static_cast<std::size_t>(axis)];
  const Path& best = a.paths.front();
  const std::vector<Candidate> candidates = InEffectOrNewer(a.candidates, best.in_effect);
  const double max_step = Of(options_.max_step_deg, axis);
  const double play = Of(options_.play_deg, axis);
  double sum = 0, weights = 0;
  for (const Candidate& c : candidates) {
    sum += c.prior * Reached(best.views, max_step, play, c.deg).output_deg;
    weights += c.prior;
  }
  return weights > 0 ? sum / weights
                     : Reached(best.views, max_step, play, candidates.front().deg).output_deg;
}

ServoTargets ServoBelief::Expose(std::int64_t frame) {
  exposed_ = frame;
  for (int axis = 0; axis < 2; ++axis) FillCandidates(axis);
  believed_ = {Expected(0), Expected(1)};
  return believed_;
}

double ServoBelief::Predict(const std::deque<View>& views, double px_per_deg) const {
  // Where the swing should be now: a least-squares line (two or three views) or parabola
  // (four or more) through the recent views, frames counted from the exposed one.
  const auto view = [px_per_deg](const View& v) { return v.deg * px_per_deg + v.displacement_px; };
  const std::size_t n = views.size();
  if (n == 1) return view(views.front());
  const int terms = n >= 4 ? 3 : 2;
  Eigen::MatrixXd design(static_cast<Eigen::Index>(n), terms);
  Eigen::VectorXd u(static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    const double t = static_cast<double>(views[k].frame - exposed_);
    design(row, 0) = 1;
    design(row, 1) = t;
    if (terms == 3) design(row, 2) = t * t;
    u(row) = view(views[k]);
  }
  const Eigen::VectorXd fit = design.colPivHouseholderQr().solve(u);
  return fit(0);
}

void ServoBelief::ScoreScales(Axis* a, double px_per_deg) {
  // The best path's newest view against the extrapolation of the ones before it, under each
  // scale.
  std::deque<View> views = a->paths.front().views;
  if (views.size() < 3) return;
  const View newest = views.back();
  views.pop_back();
  for (std::size_t h = 0; h < scales_.size(); ++h) {
    const double theta = scales_[h] * px_per_deg;
    const double miss = newest.deg * theta + newest.displacement_px - Predict(views, theta);
    a->scale_miss_sq[h] += kSpreadRate * (miss * miss - a->scale_miss_sq[h]);
  }
  ++a->scored;
}

double ServoBelief::Sharpness(const Axis& a) const {
  if (a.scored < kMinScaleFrames) return 0;
  const auto [low, high] = std::minmax_element(a.scale_miss_sq.begin(), a.scale_miss_sq.end());
  return *low > 0 ? *high / *low - 1 : 0;
}

void ServoBelief::ChooseScales() {
  // Both axes look through one lens, so a calibration off by a factor is off by it on both:
  // an axis whose views tell the scales apart far less well than the other's takes the
  // other's. (Servos whose degrees differ per axis are left to the controller's estimate,
  // which each axis fits alone once its swing is large enough.)
  const std::array<double, 2> sharpness = {Sharpness(axes_[0]), Sharpness(axes_[1])};
  std::array<bool, 2> own{};
  for (std::size_t axis = 0; axis < 2; ++axis) {
    own[axis] = sharpness[axis] >= kMinSharpness &&
                sharpness[axis] >= kOwnSharpnessShare * sharpness[1 - axis];
    if (!own[axis]) continue;
    Axis& a = axes_[axis];
    const auto best = static_cast<std::size_t>(
        std::min_element(a.scale_miss_sq.begin(), a.scale_miss_sq.end()) - a.scale_miss_sq.begin());
    if (a.scale_miss_sq[best] < kScaleMargin * a.scale_miss_sq[a.scale]) a.scale = best;
  }
  for (std::size_t axis = 0; axis < 2; ++axis) {
    if (!own[axis] && own[1 - axis]) axes_[axis].scale = axes_[1 - axis].scale;
  }
}

void ServoBelief::ExtendPaths(Axis* a, int axis, double displacement_px, double px_per_deg) const {
  const double max_step = Of(options_.max_step_deg, axis);
  const double play = Of(options_.play_deg, axis);
  // A path's cost grows by each frame's miss against its own extrapolation (Gaussian, with
  // the spread the best path has missed by lately) and by how unlikely the delay it chose
  // is; the kPaths cheapest survive.
  const double spread_sq = std::max(kMinSpreadPx * kMinSpreadPx, a->miss_sq);
  struct Extended {
    Path path;
    double miss;  // [px] NaN: nothing to extrapolate from
    bool chose;   // there were several candidates to choose from
  };
  std::vector<Extended> next;
  for (const Path& path : a->paths) {
    const std::vector<Candidate> allowed = InEffectOrNewer(a->candidates, path.in_effect);
    double prior_sum = 0;
    for (const Candidate& c : allowed) prior_sum += c.prior;
    const double predicted = path.views.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                : Predict(path.views, px_per_deg);
    for (const Candidate& c : allowed) {
      const Pose pose = Reached(path.views, max_step, play, c.deg);
      const double deg = pose.output_deg;
      Extended e{path, deg * px_per_deg + displacement_px - predicted, allowed.size() > 1};
      if (std::isfinite(e.miss)) e.path.cost += 0.5 * e.miss * e.miss / spread_sq;
      if (prior_sum > 0 && c.prior > 0) e.path.cost -= std::log(c.prior / prior_sum);
      e.path.in_effect = c.order;
      e.path.views.push_back({exposed_, deg, displacement_px, pose.shaft_deg});
      while (e.path.views.size() > kViews) e.path.views.pop_front();
      next.push_back(std::move(e));
    }
  }
  std::stable_sort(next.begin(), next.end(),
                   [](const Extended& l, const Extended& r) { return l.path.cost < r.path.cost; });
  // Paths that agree on the newest command in effect and on every view they keep have the
  // same future: only the likelier one is kept.
  const auto same = [](const Path& l, const Path& r) {
    if (l.in_effect != r.in_effect || l.views.size() != r.views.size()) return false;
    for (std::size_t k = 0; k < l.views.size(); ++k) {
      if (l.views[k].deg != r.views[k].deg || l.views[k].frame != r.views[k].frame ||
          l.views[k].shaft_deg != r.views[k].shaft_deg) {
        return false;
      }
    }
    return true;
  };
  std::vector<Path> kept;
  for (const Extended& e : next) {
    if (kept.size() == kPaths) break;
    if (std::none_of(kept.begin(), kept.end(), [&](const Path& k) { return same(k, e.path); })) {
      kept.push_back(e.path);
    }
  }
  const double best_cost = kept.front().cost;
  for (Path& path : kept) path.cost -= best_cost;
  const Extended& best = next.front();
  if (best.chose && std::isfinite(best.miss)) {
    a->miss_sq += kSpreadRate * (best.miss * best.miss - a->miss_sq);
  }
  a->paths = std::move(kept);
}

double ServoBelief::ResolveAxis(int axis, double displacement_px, double deg_per_px) {
  Axis& a = axes_[static_cast<std::size_t>(axis)];
  for (Path& path : a.paths) {
    if (!path.views.empty() && path.views.back().frame < exposed_ - kMaxViewGapFrames) {
      path.views.clear();
    }
  }
  // Without views to extrapolate, no path can tell the candidates apart: the belief is their
  // expected angle, while the paths keep each candidate as a hypothesis.
  const bool extrapolated = !a.paths.front().views.empty();
  const std::size_t allowed = InEffectOrNewer(a.candidates, a.paths.front().in_effect).size();
  // Before the paths move on: the mean over the candidates the best path allows.
  const double expected = extrapolated || allowed == 1 ? 0.0 : Expected(axis);
  ExtendPaths(&a, axis, displacement_px, scales_[a.scale] / deg_per_px);
  // Scored only where the latency jitters: with one candidate the scale changes nothing.
  if (allowed > 1) ScoreScales(&a, 1.0 / deg_per_px);
  return extrapolated || allowed == 1 ? a.paths.front().views.back().deg : expected;
}

ServoTargets ServoBelief::Resolve(const ControlInput& input, const LensCalibration& calibration) {
  const cv::Point2d d = input.displacement_px;
  // Each axis is resolved from its own measurement; one the frame did not measure (NaN: its
  // match was not sure along it) is believed at its candidates' expected angle.
  const bool x = input.found && std::isfinite(d.x);
  const bool y = input.found && std::isfinite(d.y);
  believed_ = {x ? ResolveAxis(0, d.x, calibration.pan_deg_per_px) : Expected(0),
               y ? ResolveAxis(1, d.y, calibration.tilt_deg_per_px) : Expected(1)};
  if (x || y) ChooseScales();
  return believed_;
}

ServoTargets ServoBelief::ShaftCommand(const ServoTargets& output_target) const {
  // The horn lags a shaft that turns one way by half the play: commanded at the target, the
  // servo stopped that short of it on every move (simulated 0.1° play: 0.5 px behind the
  // swing on both axes).
  const auto axis_command = [this](int axis, double target) {
    const double half = Of(options_.play_deg, axis) / 2;
    const double output = Of(believed_, axis);
    if (half == 0 || !std::isfinite(output)) return target;
    if (target > output) return target + half;
    if (target < output) return target - half;
    const std::deque<View>& views = axes_[static_cast<std::size_t>(axis)].paths.front().views;
    return views.empty() || views.back().frame != exposed_ ? target : views.back().shaft_deg;
  };
  return {axis_command(0, output_target.pan_deg), axis_command(1, output_target.tilt_deg)};
}

void ServoBelief::ForgetViews() {
  for (Axis& a : axes_) a.paths = {Path{{}, a.paths.front().in_effect, 0}};
}

double ServoBelief::scale(int axis) const {
  return scales_[axes_[static_cast<std::size_t>(axis)].scale];
}

LensCalibration ServoBelief::Scaled(const LensCalibration& calibration) const {
  return {calibration.pan_deg_per_px / scale(0), calibration.tilt_deg_per_px / scale(1)};
}

std::vector<double> ServoBelief::Candidates(int axis) const {
  std::vector<double> out;
  for (const Candidate& c : axes_[static_cast<std::size_t>(axis)].candidates) out.push_back(c.deg);
  return out;
}

}  // namespace kapfix
