// Which iterate Support Slimming returns (slimming.h).
//
//   IterateChoice choice(input_stats);
//   if (choice.offer(stats)) { ...keep this iterate... }
//
// The iterate that needs the least support: by the support model's estimate of what the slicer
// builds (support_model.h) when the run measures it (IterationStats::support_estimate > 0 for the
// input), else by the shadow volume (overhang.h), the cruder estimate. The risky area breaks ties,
// and a later iterate wins a full tie. An iterate with more risky area than the input never
// qualifies: neither may get worse than the input's. When no iterate beats the input, the input is
// the result. (Bending a T's arms or a mushroom's rim can shrink the risky area while the
// overhangs left move higher and need more support; and the slicer closes small gaps in an
// overhang's footprint, so cutting risky area can save nothing: the support decides.)
// An iterate whose crease share exceeds max_crease_share_pct (when > 0) never qualifies either.
// In: the input's statistics (iteration 0) and the crease limit (%), then each iterate's
// (risky_area mm², support_estimate or shadow_volume mm³, crease_share_pct, which only the
// iterates reads_creases() names need). Out: offer() is true when the iterate is the best so far.
#pragma once

#include <cmath>

#include "core/slimming.h"

namespace slim {

class IterateChoice {
 public:
  explicit IterateChoice(const IterationStats& input, double max_crease_share_pct = 0.0)
      : by_model_(input.support_estimate > 0.0), max_crease_(max_crease_share_pct), input_risky_(input.risky_area),
        best_support_(support(input)), best_risky_(input.risky_area) {}

  bool offer(const IterationStats& s) {
    // An iterate the model could not measure (NaN) never qualifies.
    const bool creased = max_crease_ > 0.0 && s.crease_share_pct > max_crease_;
    const bool qualifies = s.risky_area <= input_risky_ && !(by_model_ && std::isnan(s.support_estimate)) && !creased;
    const double need = support(s);
    if (creased && need < best_support_) ++passed_over_;
    if (!qualifies || !(need < best_support_ || (need == best_support_ && s.risky_area <= best_risky_))) return false;
    best_support_ = need;
    best_risky_ = s.risky_area;
    return true;
  }

  // Whether offer() reads the iterate's crease share: only an iterate that needs no more support
  // than the best so far can be chosen or passed over (the share costs a pass over every edge).
  bool reads_creases(const IterationStats& s) const { return max_crease_ > 0.0 && !(support(s) > best_support_); }

  // Iterates that needed less support than the best so far but creased past the limit.
  int passed_over() const { return passed_over_; }

 private:
  double support(const IterationStats& s) const { return by_model_ ? s.support_estimate : s.shadow_volume; }

  bool by_model_;
  double max_crease_;
  int passed_over_ = 0;
  double input_risky_, best_support_, best_risky_;
};

}  // namespace slim
