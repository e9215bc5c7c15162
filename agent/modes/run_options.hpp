#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "agent/config/agent_config.hpp"
#include "agent/modes/report_messages.hpp"
#include "common/control/controller.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/lost_lock_ssp.hpp"
#include "common/selection/patch_size_selection.hpp"
#include "common/selection/slice_selection_options.hpp"
#include "common/sim/simulated_platform.hpp"

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
// How an SSP report names the search that made it.
SliceReportContext MakeSliceReportContext(const SearchConfig& search);
// SSP after a lost lock (FixateMode, and the benchmark's flights): the wait from
// search.ssp_after_lost_s at the camera's rate (0 = off), SSP's run as long as its free swing.
LostLockSspOptions MakeLostLockSspOptions(const AgentConfig& config);
// The thesis's candidate sizes that fit into a `plane` of this size.
PatchSizeSelectionOptions MakePatchSizeSelectionOptions(const SearchConfig& search, cv::Size plane);

// The simulated platform `kapfix-agent --sim` flies: the motion, seed, frame size, lens, servo
// limits and speed of the configuration, with its world's disturbances applied (the world's
// calibration error scales the truth against the lens profile the controller believes).
SimulatedPlatformOptions::Motion ToPlatformMotion(MotionKind kind);
SimulatedPlatformOptions MakePlatformOptions(const AgentConfig& config);

// The simulated world is defined in frames and pixels, for the built-in configuration's
// camera (30 frames/s, a lens of 0.1 deg/px): its swing's period is 40 frames and its
// amplitude 100 px whatever the camera. A configuration with another frame rate or lens
// therefore flies a swing physically faster or wider than the built-in one (resources/
// kite.json: 60 frames/s and 0.17 deg/px make it 2× faster and 1.7× wider in angle), and its
// figures do not compare with the built-in's. This says so in one line, or nothing when the
// camera is the built-in's. Left for later: a world defined in seconds and degrees.
std::optional<std::string> SimulatedWorldScaleNote(const AgentConfig& config);

// The closed loop `kapfix-agent --sim --mode fixate` flies with this configuration, as
// EvaluateClosedLoop's options, so that the loop benchmark flies what the agent flies and the
// two cannot part (issue 9: they did, on the gains' rate limit): its platform, controller kind
// and gains (the rate limit and dead band included), search and fixation, frame period and
// free-swing length. The configuration's world goes to `world`, which EvaluateClosedLoop
// applies, not into `platform`. Not carried: --blur's shutter time follows the photo exposure
// in the agent and is half a frame in the evaluation; with a calibration error the agent
// scales the true deg/px (the swing in pixels grows with it) where the evaluation scales the
// controller's belief (the same swing, a wrong belief): the same error ratio either way.
ClosedLoopOptions MakeClosedLoopOptions(const AgentConfig& config);

// Whether two settings build the same fixation loop (search, controller kind, active lens)
// but for the controller's gains, which the loop takes without a rebuild. A setting re-sent
// unchanged, or new gains, must not reset the controller (issue 15, item 7).
bool SameLoop(const AgentConfig& a, const AgentConfig& b);

}  // namespace kapfix::agent
