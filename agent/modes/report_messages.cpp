#include "agent/modes/report_messages.hpp"

#include <cmath>

namespace kapfix::agent {
namespace {

void FillAxis(const std::optional<AxisCalibration>& fit, kapfix::v1::AxisCalibration* axis) {
  if (!fit) return;
  axis->set_units_per_px_median(fit->units_per_px_median);
  axis->set_units_per_px_fit(fit->units_per_px_fit);
  axis->set_residual_px(fit->residual_px);
  axis->set_samples(static_cast<std::uint32_t>(fit->samples));
  axis->set_valid(std::isfinite(fit->units_per_px_fit) && fit->units_per_px_fit != 0.0);
}

}  // namespace

kapfix::v1::SliceScoreKind ToProto(SliceScoreKind kind) {
  switch (kind) {
    case SliceScoreKind::kDc:
      return kapfix::v1::SLICE_SCORE_KIND_DC;
    case SliceScoreKind::kDcHysteresis:
      return kapfix::v1::SLICE_SCORE_KIND_DC_HYSTERESIS;
    case SliceScoreKind::kFft:
      return kapfix::v1::SLICE_SCORE_KIND_FFT;
    case SliceScoreKind::kSingleShot:
      return kapfix::v1::SLICE_SCORE_KIND_SINGLE_SHOT;
  }
  return kapfix::v1::SLICE_SCORE_KIND_UNSPECIFIED;
}

kapfix::v1::SliceReport MakeSliceReport(const SliceSelection& selection,
                                        const SliceReportContext& context,
                                        const SwingProgress& progress) {
  kapfix::v1::SliceReport report;
  std::vector<std::uint32_t> rank(selection.slices.size() + 1, 0);
  for (std::size_t r = 0; r < selection.ranking.size(); ++r) {
    const auto index = static_cast<std::size_t>(selection.ranking[r]);
    if (index < rank.size()) rank[index] = static_cast<std::uint32_t>(r + 1);
  }
  for (const SliceScore& slice : selection.slices) {
    kapfix::v1::SliceScore* out = report.add_slices();
    out->set_index(static_cast<std::uint32_t>(slice.index));
    out->set_dc(static_cast<std::uint32_t>(slice.dc));
    out->set_dc_hysteresis(static_cast<std::uint32_t>(slice.dc_hysteresis));
    out->set_fft(slice.fft);
    out->set_single_shot(static_cast<float>(slice.single_shot));
    out->set_ambiguous(slice.ambiguous);
    for (const double sample : slice.graph.samples) out->add_graph_px(static_cast<float>(sample));
    out->set_rank(rank[static_cast<std::size_t>(slice.index)]);
  }
  report.set_recommended_slice(static_cast<std::uint32_t>(selection.best_slice));
  report.set_progress_done(static_cast<std::uint32_t>(progress.done));
  report.set_progress_total(static_cast<std::uint32_t>(progress.total));
  report.set_finished(progress.finished);
  report.set_deadline_reached(progress.deadline_reached);
  report.set_score(ToProto(context.score));
  report.set_dc_hysteresis_px(static_cast<float>(context.hysteresis_px));
  report.set_patch_size_px(static_cast<std::uint32_t>(context.patch_size_px));
  report.set_strategy(context.strategy);
  return report;
}

kapfix::v1::PssReport MakePssReport(const PatchSizeSelection& selection,
                                    const std::vector<std::vector<double>>& graphs,
                                    const SwingProgress& progress) {
  kapfix::v1::PssReport report;
  for (std::size_t i = 0; i < selection.sizes.size(); ++i) {
    const PatchSizeScore& size = selection.sizes[i];
    kapfix::v1::PatchSizeScore* out = report.add_candidates();
    out->set_patch_size_px(static_cast<std::uint32_t>(size.size));
    out->set_dc(static_cast<std::uint32_t>(size.dc));
    out->set_fft(size.fft);
    if (i < graphs.size()) {
      for (const double sample : graphs[i]) out->add_graph_px(static_cast<float>(sample));
    }
  }
  report.set_recommended_patch_size_px(static_cast<std::uint32_t>(selection.best_size));
  report.set_progress_done(static_cast<std::uint32_t>(progress.done));
  report.set_progress_total(static_cast<std::uint32_t>(progress.total));
  report.set_finished(progress.finished);
  report.set_deadline_reached(progress.deadline_reached);
  return report;
}

kapfix::v1::CalibrationReport MakeCalibrationReport(const std::string& lens_profile,
                                                    const std::optional<AxisCalibration>& pan,
                                                    const std::optional<AxisCalibration>& tilt,
                                                    int moves_done, int moves_total,
                                                    bool finished) {
  kapfix::v1::CalibrationReport report;
  report.set_lens_profile(lens_profile);
  FillAxis(pan, report.mutable_pan());
  FillAxis(tilt, report.mutable_tilt());
  report.set_progress_done(static_cast<std::uint32_t>(moves_done));
  report.set_progress_total(static_cast<std::uint32_t>(moves_total));
  report.set_finished(finished);
  return report;
}

}  // namespace kapfix::agent
