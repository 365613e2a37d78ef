// Which iterate Support Slimming returns (slimming.h).
//
//   IterateChoice choice(input_stats, judge, max_crease_share_pct, min_saving_pct, max_mean_displacement_mm);
//   if (choice.offer(stats)) { ...keep this iterate... }
//
// The iterate that needs the least support, by the judge: the support model's estimate of what
// the slicer builds (support_model.h; the caller measured the input's support as more than 0), or
// the shadow volume (overhang.h), the cruder estimate. The risky area breaks ties,
// and a later iterate wins a full tie. An iterate with more risky area than the input never
// qualifies: neither may get worse than the input's. When no iterate beats the input, the input is
// the result. (Bending a T's arms or a mushroom's rim can shrink the risky area while the
// overhangs left move higher and need more support; and the slicer closes small gaps in an
// overhang's footprint, so cutting risky area can save nothing: the support decides.)
// An iterate whose crease share exceeds max_crease_share_pct (when set) never qualifies either,
// nor one whose surface vertices moved further than max_mean_displacement_mm on average (when set:
// the deformation spreads over the part while the last steps buy little support),
// and by the support model neither does one that saves less than min_saving_pct (%) of the
// input's support: a saving within the model's error is not worth a change of shape. That saving
// must hold both over the grid phases (the mean, which decides between iterates) and at the
// slicer's own phase for the part as placed (support_slicer_phase, when measured): a saving the
// mean finds only at phases the slicer does not lay is not one it builds.
// In: the input's statistics (iteration 0), the judge, the crease limit (%, none: no limit) and
// the least saving (%), then each iterate's (risky_area mm², support_estimate or shadow_volume
// mm³, support_slicer_phase mm³, crease_share_pct, which only the iterates reads_creases() names
// need; an estimate or share not measured is none). Out: offer() is true
// when the iterate is the best so far; best_unsaved_pct() the largest saving (%) that fell short
// of the least, for the report.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/optimizer/slimming_result.h"

namespace slim {

class IterateChoice {
 public:
  IterateChoice(const IterationStats& input, ResultJudge judge, std::optional<double> max_crease_share_pct = std::nullopt,
                double min_saving_pct = 0.0, std::optional<double> max_mean_displacement_mm = std::nullopt)
      : by_model_(judge == ResultJudge::SupportModel), max_crease_(max_crease_share_pct),
        max_displacement_(max_mean_displacement_mm), input_risky_(input.risky_area),
        input_support_(support(input)), input_slicer_phase_(by_model_ ? input.support_slicer_phase.value_or(0.0) : 0.0),
        best_support_(input_support_), best_risky_(input.risky_area) {
    // By the model an iterate must beat the input by the least saving: it starts as the bar.
    if (by_model_ && min_saving_pct > 0.0) {
      best_support_ *= 1.0 - min_saving_pct / 100.0;
      if (input_slicer_phase_ > 0.0) slicer_phase_bar_ = (1.0 - min_saving_pct / 100.0) * input_slicer_phase_;
    }
  }

  bool offer(const IterationStats& s) {
    // An iterate the model could not measure never qualifies.
    const bool creased = max_crease_ && s.crease_share_pct && *s.crease_share_pct > *max_crease_;
    const bool displaced = max_displacement_ && s.mean_displacement > *max_displacement_;
    const bool qualifies = s.risky_area <= input_risky_ && !(by_model_ && !s.support_estimate) && !creased && !displaced;
    const double need = support(s);
    if (creased && need < best_support_) ++passed_over_;
    if (displaced && need < best_support_) ++displaced_over_;
    if (qualifies) best_unsaved_ = std::max(best_unsaved_, saving_pct(s));
    const bool saves_at_phase = !s.support_slicer_phase || *s.support_slicer_phase <= slicer_phase_bar_;
    if (!qualifies || !saves_at_phase || !(need < best_support_ || (need == best_support_ && s.risky_area <= best_risky_)))
      return false;
    best_support_ = need;
    best_risky_ = s.risky_area;
    return true;
  }

  // Whether offer() reads the iterate's crease share: only an iterate that needs no more support
  // than the best so far can be chosen or passed over (the share costs a pass over every edge).
  bool reads_creases(const IterationStats& s) const { return max_crease_ && !(support(s) > best_support_); }

  // Iterates that needed less support than the best so far but creased past the limit.
  int passed_over() const { return passed_over_; }
  // Iterates that needed less support than the best so far but moved the surface too far.
  int displaced_over() const { return displaced_over_; }

  // The largest saving (% of the input's support; by the model the smaller of the phase mean's
  // and the slicer phase's) of an iterate that qualified but for the least saving; 0 when none
  // saved anything. Read when no iterate was chosen.
  double best_unsaved_pct() const { return best_unsaved_; }

 private:
  // NaN for an iterate the model could not measure: it compares as no better than any.
  double support(const IterationStats& s) const {
    return by_model_ ? s.support_estimate.value_or(std::numeric_limits<double>::quiet_NaN()) : s.shadow_volume;
  }
  double saving_pct(const IterationStats& s) const {
    double saved = 100.0 * (1.0 - support(s) / input_support_);
    if (input_slicer_phase_ > 0.0 && s.support_slicer_phase)
      saved = std::min(saved, 100.0 * (1.0 - *s.support_slicer_phase / input_slicer_phase_));
    return std::max(0.0, saved);
  }

  bool by_model_;
  std::optional<double> max_crease_, max_displacement_;
  int passed_over_ = 0, displaced_over_ = 0;
  double input_risky_, input_support_, input_slicer_phase_, best_support_, best_risky_;
  double best_unsaved_ = 0.0;
  double slicer_phase_bar_ = std::numeric_limits<double>::infinity();  // mm³ at the slicer's phase
};

}  // namespace slim
