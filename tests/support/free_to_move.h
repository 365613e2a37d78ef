// Slimming options with the part free to move: no hold on its size and proportions
// (allow_stretch) and no limit on the result's creases or mean displacement. For the tests of a
// mechanism (the ladder's choice, a guard, invariance under scale and position) that needs the
// part to move far; the defaults' own holds are tested in slimming_shape_test.cpp.
#pragma once

#include "core/optimizer/slimming_options.h"

namespace slim::test {

inline SlimmingOptions free_to_move() {
  SlimmingOptions o;
  allow_stretch(o);
  o.result.max_crease_share_pct.reset();
  o.result.max_mean_displacement_pct.reset();
  return o;
}

}  // namespace slim::test
