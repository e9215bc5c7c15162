#include "common/evaluation/aim_floor.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/control/servo_belief.hpp"

namespace kapfix {

double AimFloorRms(const std::vector<cv::Point2d>& open_offsets_px, int lead_frames,
                   int lead_jitter_frames) {
  if (lead_frames < 1 || lead_jitter_frames < 0) {
    throw std::invalid_argument("aim floor: lead must be ≥ 1 and jitter ≥ 0 frames, got " +
                                std::to_string(lead_frames) + " and " +
                                std::to_string(lead_jitter_frames));
  }
  const std::vector<double> shares = DelayShares(lead_jitter_frames);
  const int n = static_cast<int>(open_offsets_px.size());
  const int spread = lead_jitter_frames;
  // The best aim of the command sent after frame t.
  const auto aim = [&](int t) {
    cv::Point2d mean(0, 0);
    for (int k = 0; k <= spread; ++k) mean += shares[k] * open_offsets_px[t + lead_frames + k];
    return mean;
  };
  double sum = 0;
  int counted = 0;
  // Frame s shows the command sent after s − lead − k; that one aimed up to frame s + spread − k.
  for (int s = lead_frames + spread; s + spread < n; ++s) {
    double expected = 0;
    for (int k = 0; k <= spread; ++k) {
      const cv::Point2d miss = open_offsets_px[s] - aim(s - lead_frames - k);
      expected += shares[k] * miss.dot(miss);
    }
    sum += expected;
    ++counted;
  }
  return counted == 0 ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(sum / counted);
}

}  // namespace kapfix
