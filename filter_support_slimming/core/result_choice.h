// Which iterate Support Slimming returns (slimming.h).
//
//   IterateChoice choice(input_report);
//   if (choice.offer(stats)) { ...keep this iterate... }
//
// The iterate whose support, estimated by its shadow volume (overhang.h), is least; the risky
// area breaks ties (an iterate with no overhang left, or only plate-level ones), and a later
// iterate wins a full tie. An iterate with more risky area than the input never qualifies:
// neither measure may get worse than the input's. Bending a T's arms or a mushroom's rim can
// shrink the risky area while the overhangs left move higher and need more support, which is why
// the shadow volume decides. When no iterate beats the input, the input is the result.
// In: the input's OverhangReport, then each iterate's IterationStats (risky_area mm², shadow_volume
// mm³). Out: offer() is true when the iterate is the best so far.
#pragma once

#include "core/overhang.h"
#include "core/slimming.h"

namespace slim {

class IterateChoice {
 public:
  explicit IterateChoice(const OverhangReport& input)
      : input_risky_(input.risky_area), best_shadow_(input.shadow_volume), best_risky_(input.risky_area) {}

  bool offer(const IterationStats& s) {
    const bool qualifies = s.risky_area <= input_risky_;
    if (!qualifies || !(s.shadow_volume < best_shadow_ || (s.shadow_volume == best_shadow_ && s.risky_area <= best_risky_)))
      return false;
    best_shadow_ = s.shadow_volume;
    best_risky_ = s.risky_area;
    return true;
  }

 private:
  double input_risky_, best_shadow_, best_risky_;
};

}  // namespace slim
