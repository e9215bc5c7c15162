#pragma once

#include <string>

namespace kapfix::agent {

// How one axis's angle becomes a pulse on one controller channel. Hobby servos take a pulse
// every ~20 ms whose width sets the angle; 1500 µs is the usual centre and ~1000 µs spans
// ~90 deg, but every servo and linkage differs, hence a per-channel mapping.
struct ServoChannelMapping {
  int channel = 0;          // controller output (Maestro 0…23, PCA9685 0…15)
  double center_us = 1500;  // [µs] pulse at 0 deg
  double us_per_deg = 10;   // [µs/deg] negative reverses the direction
  double min_us = 1000;     // [µs] narrowest pulse ever sent (last-resort guard)
  double max_us = 2000;     // [µs] widest pulse ever sent

  // Finite values, 0 ≤ channel < channel_count, 0 < |us_per_deg| ≤ 100,
  // 400 ≤ min_us < max_us ≤ 2600 (wider pulses drive most servos into their end stops) and
  // center_us inside [min_us, max_us].
  bool IsValid(int channel_count, std::string* error) const;

  // center_us + deg · us_per_deg, clamped to [min_us, max_us] [µs]. The limits proper are
  // ServoLimits' job; this clamp only keeps a bad mapping from driving a servo into its stop.
  double PulseUs(double deg) const;
};

}  // namespace kapfix::agent
