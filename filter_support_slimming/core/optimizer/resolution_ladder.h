// Support Slimming at a ladder of voxel resolutions, and the one result it keeps.
//
//   for (int resolution : ladder_resolutions(options, input.F.rows())) { ...slim at it... }
//   if (prefer(candidate, kept)) kept = candidate;
//
// Why: the voxel grid decides which parts of the surface can bend on their own (a thin limb, a
// chin or an ear shares its tets with what lies next to it), and so where the deviation budget
// goes. Which grid frees what matters is a matter of the part: on the corpus's 11 organic models
// at the 5% budget, PrusaSlicer's support fell by 22.9% at 24 cells along the longest side, 25.0%
// at 32 and 23.6% at 48 (means over 4 turns), but model by model the best of the three beat 24
// alone by up to 24 points (the long-necked creature: -26.5% at 24, -50.3% at 32). The support
// model tells them apart (within about 2 points of the slicer's change, support_model.h), so a run
// slims at each and keeps the result it predicts needs the least support: -27.1% on those models
// (docs/slicer-frontier.md).
//
// Inputs
//   options  SlimmingOptions: resolution (the first rung), domain, method, max_iterations and
//            coherence.resolution_ladder (the other rungs as multiples of the resolution) and
//            coherence.resolution_ladder_max_faces.
//   faces    the input's face count.
// Outputs
//   ladder_resolutions  the voxel resolutions to slim at, in order: options.resolution first, then
//                       each multiple rounded to the nearest cell, duplicates dropped. Only the
//                       first when the ladder is off: no multiples, the Paper method, no support
//                       model to choose by (choose_by_support_model), the TetGen domain (no
//                       voxels), an iteration limit of 0, or more faces than the cap (the
//                       embedding of a large mesh dominates each run: a 1.2M-face part must
//                       slim in 5 s).
//   ladder_line         one line for the CLI's summary and the filter's log: the resolution the
//                       result came from and, with a ladder, each rung's estimate (mm³) or why it
//                       did not run. A finer rung that is refused (too large for the memory budget)
//                       or fails is left out; the first is the user's resolution, and its refusal
//                       or failure is the run's (slim_supports throws).
//   prefer              true when candidate needs less support than kept by the support model
//                       (support_after_mm3, the phase mean each run minimises); a tie keeps kept,
//                       the coarser grid. Each run's result already saves the least saving or is
//                       the input (result_choice.h), so the kept one does too.
// Cost: one slimming per rung; at 2x the resolution a run costs 4-8x (8x the tets): the sample
// bunny slims in 1.55 s instead of 0.16 s, the 70k-face bunny in 3.6 s instead of 0.74 s
// (docs/speed.md).
#pragma once

#include <string>
#include <vector>

#include "core/optimizer/slimming_options.h"
#include "core/optimizer/slimming_result.h"

namespace slim {

std::vector<int> ladder_resolutions(const SlimmingOptions& options, long faces);

bool prefer(const SlimmingResult& candidate, const SlimmingResult& kept);

std::string ladder_line(const SlimmingResult& result);

}  // namespace slim
