#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace kapfix {

// [px] The aim floor: the RMS view error of a loop that knows the open-loop swing exactly,
// every future frame included, and whose servos do exactly what they are told, but which
// cannot know which latency each command will take. A command sent after frame t is the one
// in effect at frame t + lead_frames + k with probability DelayShares(lead_jitter_frames)[k];
// the aim that misses least is the mean of the view over those frames, weighted so, and what
// is left is the part of the swing no controller can remove (issue 9: a command lands up to
// lead_jitter_frames early or late). 0 without jitter. A lower bound for any controller in
// that world: it leaves out the forecast's error, the matcher's, the servo's speed and play.
//
// open_offsets_px: where the motion alone puts the view, one per frame (any constant origin).
// Frames whose aim would need a view before the first or after the last are not counted.
// Throws std::invalid_argument for lead_frames < 1 or lead_jitter_frames < 0; returns NaN
// when no frame can be counted.
double AimFloorRms(const std::vector<cv::Point2d>& open_offsets_px, int lead_frames,
                   int lead_jitter_frames);

}  // namespace kapfix
