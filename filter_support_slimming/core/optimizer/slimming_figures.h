// Every figure of a Support Slimming run in one place, for the CLI's summary and JSON report and
// the filters' log and outputs: what the support needs, before and after, and what the shape paid.
//
//   SlimmingFigures f = slimming_figures(before, result, reference_diagonal);
//
// Inputs
//   before              the surface the run started from (the input, or the input turned into
//                       its print pose); result.surface is the slimmed one (same faces).
//   result              slim_supports' result.
//   reference_diagonal  the bounding-box diagonal (mm) the percentages are of: the part as the
//                       user gave it (the pose does not change the budget; oriented_slimming.h).
// Output (SlimmingFigures): mm, mm², mm³ and %; support_* from the support model (0 when the run
//   did not measure it); the shape's cost from result.shape (the run's shape_metrics.h figures:
//   volume, creases), proportions.h (extents, height, folds, the affine map's departure from a
//   rigid motion) and surface_distance.h (the Hausdorff distance of the slimming); the budget as
//   given and as a length. Cost: one distance pass over the surfaces, one pass over the faces.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/geometry/surface.h"
#include "core/optimizer/slimming_result.h"

namespace slim {

// A flat record of numbers, as the JSON report and MeshLab's filter outputs carry them: a figure
// the run did not measure (SlimmingResult's none) is 0 here.
struct SlimmingFigures {
  double support_estimate_before_mm3 = 0.0, support_estimate_after_mm3 = 0.0;
  double support_change_pct = 0.0;  // of the estimate; 0 when not measured
  double support_slicer_phase_before_mm3 = 0.0, support_slicer_phase_after_mm3 = 0.0;  // at the slicer's
  double support_slicer_phase_change_pct = 0.0;  // own grid phase (slimming.h); 0 when not measured
  double shadow_volume_before_mm3 = 0.0, shadow_volume_after_mm3 = 0.0;
  double risky_area_before_mm2 = 0.0, risky_area_after_mm2 = 0.0;
  double volume_before_mm3 = 0.0, volume_after_mm3 = 0.0, volume_change_pct = 0.0;
  double crease_share_pct = 0.0, crease_p99_deg = 0.0;
  // Proportions (proportions.h), result against the surface the run started from: each
  // bounding-box extent's change and the height's (along the print direction), %; how far the
  // best-fit affine map departs from a rigid motion, %; the faces folded over.
  double extent_change_x_pct = 0.0, extent_change_y_pct = 0.0, extent_change_z_pct = 0.0;
  double height_change_pct = 0.0, affine_departure_pct = 0.0;
  long folded_faces = 0;
  double hausdorff_mm = 0.0, hausdorff_pct = 0.0;
  double max_displacement_mm = 0.0, mean_displacement_mm = 0.0;
  double mean_displacement_pct = 0.0;  // of the reference diagonal
  double budget_mm = 0.0, budget_pct = 0.0;  // 0: no budget
  long open_edges = 0;  // edges of the input used by one face: the borders of its holes
  int iterations = 0;
  int resolution = 0;   // the voxel resolution the result came from (0: TetGen; resolution_ladder.h)
  double seconds = 0.0;
};

SlimmingFigures slimming_figures(const Surface& before, const SlimmingResult& result, double reference_diagonal);

// What a user should know of an open mesh (open_edges > 0): slicers close or drop its holes slice
// by slice, which the support estimate counts. One sentence; empty for a closed mesh.
std::string open_mesh_note(long open_edges);

// Every figure by name, in the order above: the keys of support-slim's --report and of the
// Support Slimming filter's outputs (docs/usage.md lists them with their units).
std::vector<std::pair<const char*, double>> named_figures(const SlimmingFigures& figures);

}  // namespace slim
