#pragma once

#include <opencv2/core.hpp>

namespace kapfix {

// Brings a current plane to the brightness of the plane a reference was stored from, before
// the SSD compares them (issue 9). SSD is not brightness-invariant: under a gain g the
// distance at a shift s carries a term g² · Σ current(s)², which varies with s and pulls the
// minimum towards the darker (g > 1) or brighter (g < 1) neighbourhood. An auto-exposure step
// of 1.6 × between the reference and the frame walked pyr's full-resolution levels 10–12 px
// off the right answer at a confident coarse level (the realistic world after SSP: aero1.jpg
// 14 % of the frames 10–20 px off while the loop claimed the view).
//
// The gain is the ratio of the two planes' mean brightness over the whole frame: an exposure
// or gain change is global, and the whole frame keeps most of its content while the view is
// held (measured against the simulated camera's true gain over 500 frames of 4 photos: median
// error 0.1–1 %, at most 4 %), where the patch alone loses a share of its content to every
// pixel the view moves (up to 12 %). A frame of more than 64 k pixels is read on every k-th
// row for its mean. Immutable after construction: one per stored reference.
class ExposureCompensation {
 public:
  // The gain is held within [1/kMaxGain, kMaxGain]: beyond that the frame is not the same
  // view under another exposure (a lens cap, a frame of sky) and scaling it would only hide
  // that from the matcher's confidence.
  static constexpr double kMaxGain = 3.0;
  // Gains this close to 1 leave the plane as it is (no copy): the sensor noise is larger.
  static constexpr double kMinCorrection = 0.005;

  ExposureCompensation() = default;
  // `reference`: the plane the reference patch was taken from (8 or 16 bit, 1 or 3 channels).
  // Throws std::invalid_argument for an empty plane.
  explicit ExposureCompensation(const cv::Mat& reference);

  // [1] The factor that brings `current`'s mean brightness to the reference's, within
  // [1/kMaxGain, kMaxGain]; 1 for a black frame or a default-constructed compensation.
  double Gain(const cv::Mat& current) const;
  // `current` times Gain(current), saturated to its type; `current` itself (not a copy) when
  // the gain is within kMinCorrection of 1. `gain` (optional) receives the factor applied.
  cv::Mat Apply(const cv::Mat& current, double* gain = nullptr) const;
  // The same on a plane the caller owns, scaled where it lies (no allocation); returns the
  // factor applied (1: left as it was).
  double ApplyInPlace(cv::Mat* plane) const;

  double reference_mean() const { return reference_mean_; }

 private:
  double reference_mean_ = 0;  // [grey levels] 0: compensation off
};

}  // namespace kapfix
