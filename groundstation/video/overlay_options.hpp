#pragma once

// Which overlays the operator wants drawn over the video (issue 4: each can be switched off).

namespace kapfix::station {

struct OverlayOptions {
  bool slice_grid = true;
  bool chosen_slice = true;
  bool reference_patch = true;
  bool current_match = true;
  bool crosshair = true;
};

}  // namespace kapfix::station
