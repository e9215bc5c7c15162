#pragma once

#include <opencv2/core.hpp>

namespace kapfix {

// How the platform (kite line or boat) swings the camera's line of sight (SPEC §3).
// Implementations are pure functions of the frame index — random access gives the same
// value as sequential access — so they may be shared between threads.
class PlatformMotion {
 public:
  virtual ~PlatformMotion() = default;
  // [px] offset of the camera's line of sight from its rest direction at frame t, in scene
  // pixels; +x right, +y down. The scene content moves the opposite way in the frame.
  virtual cv::Point2d LineOfSight(int frame) const = 0;
};

}  // namespace kapfix
