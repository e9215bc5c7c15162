#pragma once

#include <opencv2/core.hpp>

#include "agent/config/agent_config.hpp"
#include "common/control/controller.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/patch_size_selection.hpp"
#include "common/selection/slice_selection_options.hpp"

namespace kapfix::agent {

// The options of common/'s runs (fixation loop, controller, SSP, PSS) as the settings give
// them: the one place where the modes turn an AgentConfig into options.

// The controller's gains, copied from the settings message by field name.
ControllerGains MakeGains(const kapfix::v1::Gains& gains);
SearchOptions MakeSearchOptions(const SearchConfig& search);
// Fixation on slice `slice` [1..slices] against the stored reference or the previous frame.
FixationOptions MakeFixationOptions(const SearchConfig& search, int slice,
                                    FixationOptions::Reference reference);
SliceSelectionOptions MakeSliceSelectionOptions(const SearchConfig& search);
// The thesis's candidate sizes that fit into a `plane` of this size.
PatchSizeSelectionOptions MakePatchSizeSelectionOptions(const SearchConfig& search, cv::Size plane);

// Whether two settings build the same fixation loop (search, controller kind, active lens)
// but for the controller's gains, which the loop takes without a rebuild. A setting re-sent
// unchanged, or new gains, must not reset the controller (issue 15, item 7).
bool SameLoop(const AgentConfig& a, const AgentConfig& b);

}  // namespace kapfix::agent
