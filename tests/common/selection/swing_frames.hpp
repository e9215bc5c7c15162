#pragma once

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <vector>

namespace kapfix::testing {

// [px] Window positions of a free pendulum swing, x(t) = A·sin(2πt/T)·e^(−t/τ) (SPEC §3,
// servos off; τ = 0: undamped), rounded to whole pixels because the frames are crops of a
// scene image.
inline std::vector<int> PendulumPositions(int frames, double amplitude_px, double period_frames,
                                          double damping_frames = 0.0) {
  std::vector<int> positions;
  for (int t = 0; t < frames; ++t) {
    const double decay = damping_frames > 0.0 ? std::exp(-t / damping_frames) : 1.0;
    positions.push_back(static_cast<int>(
        std::lround(amplitude_px * std::sin(2.0 * std::numbers::pi * t / period_frames) * decay)));
  }
  return positions;
}

// Frames of `frame` size cropped out of the centre of `scene`, the window moved by
// positions[t] along x (or y). A window moving right by p moves the content left by p.
inline std::vector<cv::Mat> SwingFrames(const cv::Mat& scene, cv::Size frame,
                                        const std::vector<int>& positions, bool along_x = true) {
  const int x0 = (scene.cols - frame.width) / 2;
  const int y0 = (scene.rows - frame.height) / 2;
  std::vector<cv::Mat> frames;
  for (const int p : positions) {
    const cv::Point origin = along_x ? cv::Point(x0 + p, y0) : cv::Point(x0, y0 + p);
    frames.push_back(scene(cv::Rect(origin, frame)).clone());
  }
  return frames;
}

// [px] The graph a perfect whole-pixel tracker reads off SwingFrames: the content's motion,
// −(p_t − p_{t−1}), for t = 1 … T.
inline std::vector<double> PerfectGraph(const std::vector<int>& positions) {
  std::vector<double> graph;
  for (std::size_t t = 1; t < positions.size(); ++t) {
    graph.push_back(-static_cast<double>(positions[t] - positions[t - 1]));
  }
  return graph;
}

// Seeded Gaussian sensor noise of `sigma` grey levels, different in every frame.
inline void AddNoise(std::vector<cv::Mat>& frames, double sigma, int seed) {
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  for (cv::Mat& frame : frames) {
    cv::Mat noise(frame.size(), CV_16SC1);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
    cv::Mat noisy;
    frame.convertTo(noisy, CV_16SC1);
    noisy += noise;
    noisy.convertTo(frame, frame.type());  // saturating
  }
}

}  // namespace kapfix::testing
