#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "common/search/search_strategy.hpp"
#include "common/selection/slice_selection.hpp"
#include "common/selection/slice_selection_options.hpp"
#include "common/selection/slice_selection_run.hpp"

namespace kapfix {

struct LostLockSspOptions {
  // [frames] the lock stays lost this long before SSP starts on the frames that follow; 0 = never.
  int after_frames = 90;
  // [frames] SSP's run, the first frame included (≥ 2): SSP's own deadline.
  int run_frames = 300;
  SliceSelectionOptions selection;  // its deadlines are unused (SliceSelectionRun leaves them to
                                    // the caller): run_frames decides

  bool IsValid(std::string* error) const;
};

// SSP re-run while the lock stays lost (SPEC §2.6: "re-run SSP ... whenever the confidence of
// the lock stays low"). A lost lock sends the servos to the centre of the swing and holds them
// there, so the frames that follow are a free swing: this runs SSP over them and says which
// slice tracks the scene best under that swing. The caller moves the fixation to it (keeping
// the view held: the same reference frame, another patch of it). Pure: feed it every frame.
//
// A weak patch (a plain wall, a dark cover with one stripe) can hold a still view and lose a
// swinging one; when it is lost, nothing else brings the view back (realistic world, first
// frame: right.jpg 36.5 px, Blender_Suzanne1.jpg 49.3 px, lost; after SSP 4.1 and 4.2).
class LostLockSsp {
 public:
  // The strategy must outlive this. Throws std::invalid_argument for invalid options.
  LostLockSsp(const SearchStrategy& strategy, LostLockSspOptions options);

  // Whether the lock is lost on a frame, and the frame's plane (single channel, as SSP
  // searches), asked for only while a run takes frames: a held lock costs nothing. Returns
  // SSP's result on the frame its run ends. A frame with the lock held ends a lost stretch
  // and drops a run in progress.
  std::optional<SliceSelection> See(bool lock_lost, const std::function<cv::Mat()>& plane);

  bool running() const { return run_.has_value(); }
  int lost_frames() const { return lost_frames_; }  // in the current lost stretch

 private:
  const SearchStrategy& strategy_;
  LostLockSspOptions options_;
  int lost_frames_ = 0;
  std::optional<SliceSelectionRun> run_;
};

}  // namespace kapfix
