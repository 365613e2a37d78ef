#include "filter_parts.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/optimizer/resolution_ladder.h"
#include "core/optimizer/slimming_figures.h"
#include "core/orientation/oriented_slimming.h"
#include "core/print/print_size.h"

namespace slim::plugin {

// Shown at the top of the dialog, always: short, so that every parameter and its Help line fit
// below it on a 1280x1024 screen in MeshLab 2020.09. MeshLab shows a parameter's help (its
// tooltip) both as the line the Help button reveals and on hovering, so each is one short
// sentence; docs/usage.md explains each parameter at length.
const char* const kSupportSlimmingInfo =
    "Deforms the mesh (in mm, at print size) to need less support along the <i>print direction</i>, into a new "
    "layer <i>name</i>_slimmed: the still-risky faces selected and coloured, vertex quality and colour the "
    "displacement (blue: none, red: the deviation budget).";

void add_support_slimming_parameters(const MeshModel& m, RichParameterList& par) {
  const slim::SlimmingOptions defaults;
  const float diag = dialog_diagonal(m);
  add_print_parameters(m, par);
  par.addParam(RichInt("resolution", defaults.resolution, "Voxel resolution",
                       "Voxel cells along the longest side; finer is slower. Coherent also tries 4/3 and 2 times it."));
  par.addParam(RichEnum("domain", 0, QStringList() << "Voxel" << "TetGen", "Domain",
                        "Voxel: any mesh. TetGen: a closed, clean, non-self-intersecting mesh."));
  par.addParam(RichEnum("method", 0, QStringList() << "Coherent" << "Paper", "Method",
                        "Coherent: regions turn as a body, least estimated support. Paper: as published."));
  par.addParam(RichInt("maxIterations", defaults.steps.max_iterations, "Max iterations",
                       "Upper limit; the run stops sooner when the risky area stops falling."));
  par.addParam(meshlab_api::RichAbsPerc("maxDeviation", float(defaults.budget.mm(diag).value_or(0.0)), 0.0f, diag,
                                         "Deviation budget",
                                         "Farthest any vertex may move (mm, or % of the bbox diagonal); 0: none."));
  par.addParam(RichFloat("maxCreases", float(defaults.result.max_crease_share_pct.value_or(0.0)), "Crease limit (%)",
                         "Largest creased share of the edge length; 0: no limit. Coherent only."));
  par.addParam(RichFloat("minSaving", float(defaults.result.min_support_saving_pct), "Least saving (%)",
                         "Keep the input unless support falls by this much; 0: any. Coherent only."));
  par.addParam(RichBool("allowStretch", !defaults.hold_proportions, "Allow stretch",
                        "Let the whole part move; it may come back taller and thinner."));
  par.addParam(RichInt("maxK", defaults.steps.max_k, "Max proxies per tetrahedron",
                       "K-means proxy normals per tetrahedron when no single rotation fits."));
  par.addParam(RichBool("preserveSelection", false, "Preserve selection as rigid features",
                        "Each piece of the face selection moves as one rigid body."));
  par.addParam(RichBool("optimizeOrientation", false, "Optimize the orientation first",
                        "Turn the part into its least-support pose first; ignores the print direction."));
}

namespace {

// The run's figures in the log, and every one of them in the outputs (slimming_figures.h's names;
// the first four keys are those of earlier releases, kept for scripts that read them).
void log_slimming(FilterRun& run, const slim::SlimmingResult& r, const slim::SlimmingFigures& f, bool orient) {
  const slim::IterationStats& chosen = r.history[static_cast<size_t>(r.iterations)];  // [0] is the input
  if (f.support_estimate_before_mm3 > 0.0)
    run.info(QString::asprintf("Support Slimming: support %.6g -> %.6g mm^3 (%+.1f%%; the support model's estimate of a "
                               "slicer's support%s)", f.support_estimate_before_mm3, f.support_estimate_after_mm3,
                               f.support_change_pct, orient ? ", in the print pose" : ""));
  if (f.support_slicer_phase_before_mm3 > 0.0)
    run.info(QString::asprintf("Support Slimming: at PrusaSlicer's own grid phase the model predicts %.6g -> %.6g mm^3 (%+.1f%%; "
                               "the figure above is the mean over grid phases, which the run minimises)",
                               f.support_slicer_phase_before_mm3, f.support_slicer_phase_after_mm3,
                               f.support_slicer_phase_change_pct));
  run.info(QString::asprintf(
      "Support Slimming: risky area %.6g -> %.6g mm^2 (%.2f%% -> %.2f%% of the surface, %.1f%% less)",
      r.before.risky_area, r.after.risky_area, 100.0 * r.before.risky_share(), 100.0 * r.after.risky_share(),
      r.before.risky_area > 0 ? 100.0 * (1.0 - r.after.risky_area / r.before.risky_area) : 0.0));
  run.info(QString::asprintf("Support Slimming: %d iterations in %.2f s (%s); domain %d vertices, %d tets; solver %s",
                             r.iterations, r.seconds, r.stop_reason.c_str(), r.domain_vertices, r.domain_tets,
                             r.solver_backend.empty() ? "none (no iteration ran)" : r.solver_backend.c_str()));
  run.info(QString("Support Slimming: voxel resolution ") + QString::fromStdString(slim::ladder_line(r)));
  run.info(QString::asprintf(
      "Support Slimming: displacement max %.4g, mean %.4g mm%s; volume %.6g -> %.6g mm^3 (%+.2f%%); "
      "AE %.2f%%; inverted tets %d",
      f.max_displacement_mm, f.mean_displacement_mm, orient ? " (the deformation alone, in the print pose)" : "",
      f.volume_before_mm3, f.volume_after_mm3, f.volume_change_pct, 100.0 * chosen.approximation_error,
      chosen.inverted_tets));
  run.info(QString::asprintf("Support Slimming: shape: Hausdorff %.4g mm (%.2f%% of the bbox diagonal), volume %+.2f%%, "
                             "creases %.2f%% of the edge length (99th percentile of the dihedral change %.2f deg); "
                             "budget %s",
                             f.hausdorff_mm, f.hausdorff_pct, f.volume_change_pct, f.crease_share_pct, f.crease_p99_deg,
                             f.budget_mm > 0.0 ? QString::asprintf("%.4g mm (%.3g%% of the bbox diagonal%s)", f.budget_mm,
                                                                   f.budget_pct, orient ? " as given" : "")
                                                     .toUtf8().constData()
                                               : "none"));
  run.info(QString::asprintf("Support Slimming: proportions: extents x %+.2f%%, y %+.2f%%, z %+.2f%%, height %+.2f%%; "
                             "best-fit affine map %.2f%% from a rigid motion; mean displacement %.4g mm (%.2f%% of the "
                             "bbox diagonal); %ld folded faces",
                             f.extent_change_x_pct, f.extent_change_y_pct, f.extent_change_z_pct, f.height_change_pct,
                             f.affine_departure_pct, f.mean_displacement_mm, f.mean_displacement_pct, f.folded_faces));
  if (r.inside_out) run.warning(QString("Support Slimming: ") + kInsideOutNotice);

  if (f.open_edges > 0) run.warning(QString("Support Slimming: ") + slim::open_mesh_note(f.open_edges).c_str());
  for (const auto& [key, value] : slim::named_figures(f)) run.outputs[key] = value;
  run.outputs["risky_area_before"] = r.before.risky_area;
  run.outputs["risky_area_after"] = r.after.risky_area;
  run.outputs["iterations"] = r.iterations;  // a whole number, as before
  run.outputs["max_displacement"] = f.max_displacement_mm;
}

}  // namespace

void apply_support_slimming(MeshDocument& md, const RichParameterList& par, FilterRun& run) {
  const LayerView layer(md);  // reads the layer; the document is touched only at the end
  MeshModel& input = layer.model;
  slim::SlimmingOptions options = slimming_options(par);
  if (par.getBool("preserveSelection")) {
    options.rigid_features = slim::vcg_adapters::selected_faces(input.cm);
    if (std::none_of(options.rigid_features.begin(), options.rigid_features.end(), [](bool b) { return b; }))
      throw FilterFailure("'Preserve selection as rigid features' is on but no face is selected; "
                          "select the features to keep rigid, or turn the option off");
  }
  const slim::ResultChoiceOptions choice = slim::method_applied(options).result;  // what the method reads
  run.info(QString("Support Slimming: crease limit %1, least saving %2%")
               .arg(choice.max_crease_share_pct ? QString::asprintf("%.3g%% of the edge length", *choice.max_crease_share_pct)
                                                : QString("none"))
               .arg(choice.min_support_saving_pct, 0, 'g', 3));
  if (run.progress != nullptr) {
    // MeshLab's progress bar; a host whose callback returns false cancels the run.
    options.progress = [cb = run.progress](double fraction, const std::string& message) {
      return cb(static_cast<int>(100.0 * fraction), message.c_str());
    };
  }

  // Everything is computed before the document is touched: a failure or a cancel leaves no layer.
  // With the orientation first, the part turns rigidly into its print pose and is slimmed there,
  // so the displacement and the volume change are the deformation's alone.
  const bool orient = par.getBool("optimizeOrientation");
  const std::optional<slim::OrientationOptions> orientation =
      orient ? std::optional<slim::OrientationOptions>(orientation_options(par.getFloat("alphaMax"), 1)) : std::nullopt;
  const slim::OrientedSlimming job =
      layer.run([&](const slim::Surface& surface) { return slim::slim_as_asked(surface, options, orientation); });
  const slim::SlimmingResult& r = job.slimming;
  const slim::SlimmingFigures figures = slim::slimming_figures(job.posed, r, slim::bbox_diagonal(layer.view.surface.V));
  const Displacement displacement{layer.view.to_input(r.displacement),
                                  figures.budget_mm > 0.0 ? figures.budget_mm : figures.max_displacement_mm};
  add_result_layer(md, input, "slimmed", orient ? ResultFrame::PrintPose : ResultFrame::Input, layer.positions(r.surface.V),
                   r.after.quality, r.after.risky, &displacement);
  if (orient) log_orientation(run, "Support Slimming", job.orientation, false);  // slimming notes it below

  log_slimming(run, r, figures, orient);
  if (const auto size = slim::print_size_warning(layer.view.surface.V))
    run.warning(QString("Support Slimming: ") + size->c_str() +
                "; scale it first with Filters > Normals, Curvatures and Orientation > Transform: Scale, Normalize");
}

}  // namespace slim::plugin
