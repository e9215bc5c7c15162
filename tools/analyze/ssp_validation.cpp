#include "tools/analyze/ssp_validation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/evaluation/closed_loop_evaluation.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix::analyze {

SspValidation ValidateSsp(const SspValidationSetup& setup,
                          const std::function<void(const std::string&, int, int)>& progress) {
  const SwingOptions swing = MakeSwingOptions(setup.swing);
  const cv::Size frame = swing.camera.frame_size;
  const int count = setup.selection.slice_count;
  const int patch = setup.selection.patch_size;
  if (frame.height < count || patch > std::min(frame.width, frame.height)) {
    throw std::invalid_argument("a " + std::to_string(frame.width) + "x" +
                                std::to_string(frame.height) + " frame cannot hold " +
                                std::to_string(count) + " slices with a " + std::to_string(patch) +
                                "-px patch");
  }
  // Scoring takes --literal into account; the closed loop runs the project's search by name.
  const auto strategy = MakeStrategy(setup.swing, setup.strategy);
  const cv::Mat scene = LoadScene(setup.swing.image);

  SspValidation result;
  const SwingRecording recording =
      RecordSwing(scene, swing, MakeColorChannel(setup.swing),
                  [&](int done, int total) { progress("rendering swing", done, total); });
  result.upscale = recording.upscale_factor;
  result.selection = SelectSlice(recording.planes, *strategy, setup.selection,
                                 [&](int done, int total) { progress("ssp", done, total); });
  result.groups = SliceGroups(frame, count, patch);

  ClosedLoopOptions loop = ClosedLoopOptions::ForMotion(SimulatedPlatformOptions::Motion::kKite);
  loop.platform.camera.frame_size = frame;
  const std::uint32_t seed_b =
      setup.validation_seed != 0 ? setup.validation_seed : setup.swing.seed + 1000;
  loop.platform.camera.seed = seed_b;
  loop.platform.kite.seed = seed_b;
  loop.platform.kite.gusts = setup.swing.gusts;
  loop.strategy = setup.strategy;
  loop.frames = setup.closed_loop_frames;
  loop.fixation.patch_size = patch;
  loop.fixation.slice_count = count;
  loop.fixation.sampling = setup.selection.sampling;
  loop.fixation.sampling.seed = seed_b;
  const int groups = static_cast<int>(result.groups.size());
  for (int g = 0; g < groups; ++g) {
    const int index = result.groups[g].front();
    loop.fixation.slice = index;
    const ClosedLoopFigures figures = EvaluateClosedLoop(scene, loop, [&](int done, int total) {
      progress("closed loop, slice " + std::to_string(index), g * total + done, groups * total);
    });
    result.distinct.push_back(index);
    result.fixation_rms_px.push_back(figures.rms_error_px);
    const SliceScore& s = result.selection.slices[static_cast<std::size_t>(index - 1)];
    result.predicted_badness["dc"].push_back(s.dc);
    result.predicted_badness["dc-hyst"].push_back(s.dc_hysteresis);
    result.predicted_badness["fft"].push_back(s.fft);
    result.predicted_badness["single-shot"].push_back(-s.single_shot);
  }
  const std::vector<double>& dc = result.predicted_badness["dc"];
  result.best_slice =
      result
          .distinct[static_cast<std::size_t>(std::min_element(dc.begin(), dc.end()) - dc.begin())];
  result.worst_slice =
      result
          .distinct[static_cast<std::size_t>(std::max_element(dc.begin(), dc.end()) - dc.begin())];
  for (const auto& [name, values] : result.predicted_badness) {
    try {
      result.spearman[name] = SpearmanTest(values, result.fixation_rms_px);
    } catch (const std::invalid_argument&) {
      // A constant sequence has no ranking: no entry (reported as null).
    }
  }
  return result;
}

}  // namespace kapfix::analyze
