// Support Slimming at a ladder of voxel resolutions, and the one result it keeps.
//
//   for (int resolution : ladder_resolutions(options, input.F.rows())) { ...slim at it... }
//   if (needs_less_support(candidate, kept)) kept = candidate;
//
// Why: the voxel grid decides which parts of the surface can bend on their own (a thin limb, a
// chin or an ear shares its tets with what lies next to it), and so where the deviation budget
// goes. Which grid frees what matters is a matter of the part: averaged over many parts the three
// grids do about as well, but part by part one can free a limb the others hold. The support model
// tells them apart, so a run slims at each and keeps the result it predicts needs the least
// support (docs/slicer-frontier.md has the figures).
//
// Inputs
//   options  SlimmingOptions: resolution (the first rung), domain, method, steps.max_iterations,
//            result.judge and ladder (the other rungs as multiples of the resolution, the face cap).
//   faces    the input's face count.
// Outputs
//   ladder_resolutions  the voxel resolutions to slim at, in order: options.resolution first, then
//                       each multiple rounded to the nearest cell, duplicates dropped. Only the
//                       first when the ladder is off: no multiples, the Paper method, no support
//                       model to judge by (result.judge), the TetGen domain (no voxels), an
//                       iteration limit of 0, or more faces than the cap (the embedding of a
//                       large mesh dominates each run, which must stay interactive).
//   ladder_line         one line for the CLI's summary and the filter's log: the resolution the
//                       result came from and, with a ladder, each rung's estimate (mm³) or why it
//                       did not run. A finer rung that is refused (too large for the memory budget)
//                       or fails is left out; the first is the user's resolution, and its refusal
//                       or failure is the run's (slim_supports throws).
//   needs_less_support  true when candidate needs less support than kept by the support model
//                       (support_after_mm3, the phase mean each run minimises); a tie or a run
//                       not measured keeps kept, the coarser grid. Each run's result already saves the least saving or is
//                       the input (result_choice.h), so the kept one does too.
// Cost: one slimming per rung; at 2x the resolution a run has 8x the tets and costs several times
// as much (docs/speed.md).
#pragma once

#include <string>
#include <vector>

#include "core/optimizer/slimming_options.h"
#include "core/optimizer/slimming_result.h"

namespace slim {

std::vector<int> ladder_resolutions(const SlimmingOptions& options, long faces);

bool needs_less_support(const SlimmingResult& candidate, const SlimmingResult& kept);

std::string ladder_line(const SlimmingResult& result);

}  // namespace slim
