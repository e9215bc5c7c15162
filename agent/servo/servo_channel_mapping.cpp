#include "agent/servo/servo_channel_mapping.hpp"

#include <algorithm>
#include <cmath>

namespace kapfix::agent {
namespace {

constexpr double kMinPulseUs = 400;
constexpr double kMaxPulseUs = 2600;
constexpr double kMaxUsPerDeg = 100;

}  // namespace

bool ServoChannelMapping::IsValid(int channel_count, std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (channel < 0 || channel >= channel_count) {
    return fail("channel must be 0…" + std::to_string(channel_count - 1) + ", got " +
                std::to_string(channel));
  }
  if (!std::isfinite(us_per_deg) || us_per_deg == 0 || std::abs(us_per_deg) > kMaxUsPerDeg) {
    return fail("us_per_deg must be non-zero and within ±100 µs/deg, got " +
                std::to_string(us_per_deg));
  }
  if (!std::isfinite(min_us) || !std::isfinite(max_us) || !(min_us < max_us) ||
      min_us < kMinPulseUs || max_us > kMaxPulseUs) {
    return fail("pulse range must satisfy 400 ≤ min_us < max_us ≤ 2600 µs, got [" +
                std::to_string(min_us) + ", " + std::to_string(max_us) + "]");
  }
  if (!(center_us >= min_us && center_us <= max_us)) {
    return fail("center_us " + std::to_string(center_us) + " is outside [min_us, max_us]");
  }
  return true;
}

double ServoChannelMapping::PulseUs(double deg) const {
  const double pulse = center_us + deg * us_per_deg;
  if (std::isnan(pulse)) return center_us;
  return std::clamp(pulse, min_us, max_us);
}

}  // namespace kapfix::agent
