#include "core/optimizer/slimming_figures.h"

#include "core/geometry/proportions.h"
#include "core/geometry/surface_distance.h"

namespace slim {

namespace {
double percent(double part, double whole) { return whole > 0.0 ? 100.0 * part / whole : 0.0; }
}  // namespace

SlimmingFigures slimming_figures(const Surface& before, const SlimmingResult& r, double reference_diagonal) {
  SlimmingFigures f;
  // The report is flat numbers: a figure not measured is 0 there.
  f.support_estimate_before_mm3 = r.support_before_mm3.value_or(0.0);
  f.support_estimate_after_mm3 = r.support_after_mm3.value_or(0.0);
  if (f.support_estimate_before_mm3 > 0.0)
    f.support_change_pct = 100.0 * (f.support_estimate_after_mm3 / f.support_estimate_before_mm3 - 1.0);
  f.support_slicer_phase_before_mm3 = r.support_slicer_phase_before_mm3.value_or(0.0);
  f.support_slicer_phase_after_mm3 = r.support_slicer_phase_after_mm3.value_or(0.0);
  if (f.support_slicer_phase_before_mm3 > 0.0)
    f.support_slicer_phase_change_pct = 100.0 * (f.support_slicer_phase_after_mm3 / f.support_slicer_phase_before_mm3 - 1.0);
  f.shadow_volume_before_mm3 = r.before.shadow_volume;
  f.shadow_volume_after_mm3 = r.after.shadow_volume;
  f.risky_area_before_mm2 = r.before.risky_area;
  f.risky_area_after_mm2 = r.after.risky_area;
  const ShapeChange& shape = r.shape;  // measured by the run, with the crease meter it had built
  f.volume_before_mm3 = shape.volume_input;
  f.volume_after_mm3 = shape.volume_result;
  f.volume_change_pct = shape.volume_change_pct;
  f.crease_share_pct = shape.crease_share_pct;
  f.crease_p99_deg = shape.crease_p99_deg;
  const Proportions p = proportions(before, r.surface.V, r.print_direction);
  f.extent_change_x_pct = p.extent_change_pct.x();
  f.extent_change_y_pct = p.extent_change_pct.y();
  f.extent_change_z_pct = p.extent_change_pct.z();
  f.height_change_pct = p.height_change_pct;
  f.affine_departure_pct = p.affine_departure_pct;
  f.folded_faces = p.folded_faces;
  f.hausdorff_mm = hausdorff_of_moved(before, r.surface);  // the same mesh, moved
  f.hausdorff_pct = percent(f.hausdorff_mm, reference_diagonal);
  if (r.displacement.size() > 0) {
    f.max_displacement_mm = r.displacement.maxCoeff();
    f.mean_displacement_mm = r.displacement.mean();
  }
  f.mean_displacement_pct = percent(f.mean_displacement_mm, reference_diagonal);
  f.budget_mm = r.deviation_budget_mm.value_or(0.0);
  f.budget_pct = percent(f.budget_mm, reference_diagonal);
  f.open_edges = r.open_edges;
  f.iterations = r.iterations;
  f.resolution = r.resolution;
  f.seconds = r.seconds;
  return f;
}

std::string open_mesh_note(long open_edges) {
  if (open_edges <= 0) return "";
  return "the mesh is open (" + std::to_string(open_edges) +
         " edges border holes): a slicer closes small gaps in each slice and drops what it cannot close "
         "(PrusaSlicer: gaps over 2 mm), so a wider hole empties the slices through it and the part above "
         "them is supported as if it floated; the support estimate counts that. Closing the holes first "
         "(MeshLab: Filters > Remeshing, Simplification and Reconstruction > Close Holes) avoids it";
}

std::vector<std::pair<const char*, double>> named_figures(const SlimmingFigures& f) {
  return {{"support_estimate_before_mm3", f.support_estimate_before_mm3},
          {"support_estimate_after_mm3", f.support_estimate_after_mm3},
          {"support_change_pct", f.support_change_pct},
          {"support_slicer_phase_before_mm3", f.support_slicer_phase_before_mm3},
          {"support_slicer_phase_after_mm3", f.support_slicer_phase_after_mm3},
          {"support_slicer_phase_change_pct", f.support_slicer_phase_change_pct},
          {"shadow_volume_before_mm3", f.shadow_volume_before_mm3},
          {"shadow_volume_after_mm3", f.shadow_volume_after_mm3},
          {"risky_area_before_mm2", f.risky_area_before_mm2},
          {"risky_area_after_mm2", f.risky_area_after_mm2},
          {"volume_before_mm3", f.volume_before_mm3},
          {"volume_after_mm3", f.volume_after_mm3},
          {"volume_change_pct", f.volume_change_pct},
          {"crease_share_pct", f.crease_share_pct},
          {"crease_p99_deg", f.crease_p99_deg},
          {"extent_change_x_pct", f.extent_change_x_pct},
          {"extent_change_y_pct", f.extent_change_y_pct},
          {"extent_change_z_pct", f.extent_change_z_pct},
          {"height_change_pct", f.height_change_pct},
          {"affine_departure_pct", f.affine_departure_pct},
          {"folded_faces", static_cast<double>(f.folded_faces)},
          {"hausdorff_mm", f.hausdorff_mm},
          {"hausdorff_pct", f.hausdorff_pct},
          {"max_displacement_mm", f.max_displacement_mm},
          {"mean_displacement_mm", f.mean_displacement_mm},
          {"mean_displacement_pct", f.mean_displacement_pct},
          {"budget_mm", f.budget_mm},
          {"budget_pct", f.budget_pct},
          {"open_edges", static_cast<double>(f.open_edges)},
          {"iterations", static_cast<double>(f.iterations)},
          {"resolution", static_cast<double>(f.resolution)},
          {"seconds", f.seconds}};
}

}  // namespace slim
