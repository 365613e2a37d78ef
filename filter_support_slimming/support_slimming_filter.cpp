#include "filter_parts.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/optimizer/resolution_ladder.h"
#include "core/optimizer/slimming_figures.h"
#include "core/orientation/oriented_slimming.h"
#include "core/print/print_size.h"

namespace slim::plugin {

// Shown at the top of the dialog, always: short, so that every parameter fits below it on a
// 1280x1024 screen in MeshLab 2020.09. The details are in each parameter's help, which the
// dialog's Help button shows.
const char* const kSupportSlimmingInfo =
    "Deforms the mesh (taken in mm, at print size) as rigidly as possible so that it needs less support when printed "
    "along the <i>print direction</i>. The result is a <b>new layer</b>; the input layer is not changed. "
    "The result keeps the input's vertices, their order and attributes, except: the still-risky faces "
    "are selected, face quality is <i>n&middot;d + sin(&alpha;<sub>max</sub>)</i> (negative: risky) and "
    "coloured as by <i>Overhang Analysis</i>, and vertex quality is the displacement. "
    "<i>Help</i> explains each parameter.";

void add_support_slimming_parameters(const MeshModel& m, RichParameterList& par) {
  const slim::SlimmingOptions defaults;
  add_print_parameters(m, par);
  par.addParam(RichInt("resolution", defaults.resolution, "Voxel resolution",
                       "Number of voxel cells along the longest side of the bounding box. The tetrahedral "
                       "domain is made from these cells; finer follows smaller features but runs slower. The "
                       "coherent method also slims at 4/3 and 2 times it (parts up to 300,000 faces) and keeps the "
                       "result that needs the least support (estimated; the log gives each)."));
  par.addParam(RichEnum("domain", 0, QStringList() << "Voxel" << "TetGen", "Domain",
                        "Voxel: tetrahedra from a voxel grid aligned with the print direction (works on open and "
                        "non-manifold meshes). TetGen: a constrained tetrahedralization of the surface; needs a "
                        "closed, clean, non-self-intersecting mesh."));
  par.addParam(RichEnum("method", 0, QStringList() << "Coherent" << "Paper", "Method",
                        "Each iteration turns every tetrahedron holding risky faces by the smallest rotation that "
                        "makes them self-supporting (an exact LP on the Gauss sphere; area-weighted K-means proxies "
                        "when no single rotation exists), then blends the tetrahedra back together with an "
                        "as-rigid-as-possible solve; the base stays on the build plate. Coherent (default): "
                        "neighbouring rotations agree, risky regions turn as a body in small steps, flat overhangs turn "
                        "towards their nearest edge, the volume is kept, and the result is the iterate that needs the "
                        "least support as a slicer builds it (estimated; the log gives the figure). Paper: <i>Direct Computation of Minimal Rotation for Support "
                        "Slimming</i> as written, for comparison."));
  par.addParam(RichInt("maxIterations", defaults.steps.max_iterations, "Max iterations",
                       "The largest number of local/global iterations; the run ends sooner when the risky area "
                       "stops falling. 0 only embeds the mesh and writes it back."));
  par.addParam(RichFloat("maxDeviation", float(defaults.budget.share_percent().value_or(0.0)), "Deviation budget (%)",
                         "The farthest any vertex may move, as a percentage of the bounding box diagonal. It is a "
                         "constraint, not a stopping rule: the part of a step that would take a vertex further is "
                         "rolled back, and the run goes on. 0: no budget."));
  par.addParam(RichBool("allowStretch", !defaults.hold_proportions, "Allow stretch",
                        "Off (default): the part keeps its size and proportions, and what lies away from the "
                        "overhangs that need support stays where it was. On: the whole part may move, and it may "
                        "come back taller and thinner (which buys little support). The Paper method always lets "
                        "it stretch."));
  par.addParam(RichInt("maxK", defaults.steps.max_k, "Max proxies per tetrahedron",
                       "When no single rotation can make every face in a tetrahedron self-supporting, its faces "
                       "are clustered into at most this many proxy normals (area-weighted K-means)."));
  par.addParam(RichBool("preserveSelection", false, "Preserve selection as rigid features",
                        "Each connected piece of the current face selection moves as one rigid body (the paper's "
                        "&sect;IV-B), so a feature you care about keeps its shape. The result's selection is then "
                        "the still-risky faces, as always."));
  par.addParam(RichBool("optimizeOrientation", false, "Optimize the orientation first",
                        "First turn the part into the pose that needs the least support (as Print Orientation "
                        "does, Normal effort), then slim it there. The print direction above is then ignored: "
                        "the result is in the new pose, +Z up, resting on z = 0, and the displacement counts "
                        "only the deformation."));
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
  const Eigen::VectorXd displacement = layer.view.to_input(r.displacement);
  add_result_layer(md, input, "slimmed", orient ? ResultFrame::PrintPose : ResultFrame::Input, layer.positions(r.surface.V),
                   r.after.quality, r.after.risky, &displacement);
  if (orient) log_orientation(run, "Support Slimming", job.orientation, false);  // slimming notes it below

  log_slimming(run, r, slim::slimming_figures(job.posed, r, slim::bbox_diagonal(layer.view.surface.V)), orient);
  if (const auto size = slim::print_size_warning(layer.view.surface.V))
    run.warning(QString("Support Slimming: ") + size->c_str() +
                "; scale it first with Filters > Normals, Curvatures and Orientation > Transform: Scale, Normalize");
}

}  // namespace slim::plugin
