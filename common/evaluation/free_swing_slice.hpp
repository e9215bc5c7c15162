#pragma once

#include <vector>

#include "common/fixation/fixation_loop.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/slice_selection_options.hpp"
#include "common/sim/simulated_platform.hpp"

namespace kapfix {

// SSP before fixation, as the agent runs it (SPEC §2.6; issue 9: fixating after SSP counts as
// well as from the first frame): the servos hold where they are while `frames` frames of the
// free swing are scored slice by slice with the fixation's search, patch and sampling, and the
// recommended slice is returned. The platform is left on the swing's last frame (the caller
// steps on to the frame that becomes the reference). Frames the camera drops are not scored.
// Throws std::invalid_argument for frames < 2 or a patch that does not fit the frame.
int FreeSwingSlice(SimulatedPlatform& platform, const FixationOptions& fixation,
                   const SearchStrategy& strategy, int frames);
// SSP's options for a fixation: its slices, patch, sampling and search.
SliceSelectionOptions SliceSelectionOptionsFor(const FixationOptions& fixation);
// The same SSP's ranking of every slice, best first (SliceSelection::ranking).
std::vector<int> FreeSwingRanking(SimulatedPlatform& platform, const FixationOptions& fixation,
                                  const SearchStrategy& strategy, int frames);

}  // namespace kapfix
