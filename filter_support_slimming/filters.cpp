#include "filters.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <vcg/complex/append.h>

#include "core/oriented_slimming.h"
#include "core/overhang.h"
#include "core/slimming.h"
#include "core/slimming_figures.h"
#include "core/welded_view.h"
#include "vcg_adapters/surface_adapter.h"

namespace slim::plugin {
namespace {

// ---- parameters shared by the filters --------------------------------------------------------

void add_alpha_max_parameter(RichParameterList& par) {
  par.addParam(RichFloat("alphaMax", 45.0f, "Self-supporting angle (deg)",
                         "The largest overhang, measured from the vertical, that prints without support. "
                         "Faces that lean out further are risky. Must be in [0, 90)."));
}

void add_print_parameters(const MeshModel& m, RichParameterList& par) {
  const float diag = m.cm.bbox.IsNull() ? 1.0f : m.cm.bbox.Diag();
  par.addParam(meshlab_api::RichDirection(
      "printDirection", vcg::Point3f(0, 0, 1), "Print direction",
      "The direction the part grows in while printing (the build plate's normal). It need not be unit length."));
  add_alpha_max_parameter(par);
  par.addParam(meshlab_api::RichAbsPerc("plateTolerance", 0.001f * diag, 0.0f, diag,
                                         "Build plate tolerance",
                                         "Faces whose three vertices all lie within this distance of the lowest "
                                         "point along the print direction rest on the build plate and are never "
                                         "risky."));
}

slim::OverhangOptions overhang_options(const RichParameterList& par) {
  slim::OverhangOptions o;
  const auto d = par.getPoint3m("printDirection");
  o.print_direction = Eigen::Vector3d(d[0], d[1], d[2]);
  o.alpha_max_deg = par.getFloat("alphaMax");
  o.plate_tolerance = par.getAbsPerc("plateTolerance");
  return o;
}

// The filter's parameters -> the core's options. Ranges are checked by the core, which says what
// is wrong in words the log can show.
slim::SlimmingOptions slimming_options(const RichParameterList& par) {
  slim::SlimmingOptions o;
  const slim::OverhangOptions overhang = overhang_options(par);
  o.print_direction = overhang.print_direction;
  o.alpha_max_deg = overhang.alpha_max_deg;
  o.plate_tolerance = overhang.plate_tolerance;
  o.resolution = par.getInt("resolution");
  o.domain = par.getEnum("domain") == 1 ? slim::DomainKind::TetGen : slim::DomainKind::Voxel;
  o.method = par.getEnum("method") == 1 ? slim::SlimmingMethod::Paper : slim::SlimmingMethod::Coherent;
  o.max_iterations = par.getInt("maxIterations");
  o.max_deviation_pct = par.getFloat("maxDeviation");
  o.max_k = par.getInt("maxK");
  return o;
}

// The current layer, refused when there is none or it is a point cloud.
MeshModel& current_triangle_mesh(MeshDocument& md) {
  MeshModel* m = md.mm();
  if (m == nullptr) throw FilterFailure("there is no current mesh");
  if (m->cm.fn == 0) throw FilterFailure("the mesh has no faces; it needs a triangle mesh, not a point cloud");
  return *m;
}

// The layer as the core sees it: its live vertices and faces in container order, coincident
// vertices merged (core/welded_view.h), so that faces meeting at a seam share their vertex.
// Results come back to every vertex of the layer, whose list and order never change.
struct LayerView {
  slim::Surface surface;  // the layer's own vertex and face lists
  slim::WeldedView view;
  explicit LayerView(const CMeshO& cm) : surface(slim::vcgx::to_surface(cm)), view(slim::weld_coincident(surface)) {}
  // Runs `compute` on the merged surface; a refusal that names a vertex says which numbering it uses.
  template <class Compute>
  auto run(Compute&& compute) const {
    try {
      return compute(view.surface);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(e.what() + view.vertex_number_note(e.what()));
    }
  }
  slim::Points positions(const slim::Points& view_after) const { return view.positions_to_input(surface.V, view_after); }
};

// Logged by both filters when the mesh is inside out (slim::inside_out).
const char* const kInsideOutNotice =
    "the mesh is inside out (closed, with every normal pointing inwards): it was analysed with its faces turned "
    "over; to fix the layer itself use Filters > Normals, Curvatures and Orientation > Invert Faces Orientation";

// ---- Overhang Analysis -----------------------------------------------------------------------

const char* const kOverhangAnalysisInfo =
    "Finds the faces that would need support material when the mesh is 3D printed along the given "
    "<i>print direction</i>: a face is <b>risky</b> when <i>n&middot;d + sin(&alpha;<sub>max</sub>) &lt; 0</i>, "
    "that is, when it overhangs more than the self-supporting angle &alpha;<sub>max</sub> (measured from the "
    "vertical; 45&deg; is the usual rule). Faces lying on the build plate are carried by it and never count.<br>"
    "The geometry is not changed. Each face gets quality <i>n&middot;d + sin(&alpha;<sub>max</sub>)</i> "
    "(negative means risky; plate faces get +1), coloured on a fixed ramp from -1 (red) to +1 (blue) so that "
    "colours compare across meshes; the risky faces can be selected. The log reports the risky area.<br>"
    "From <i>Direct Computation of Minimal Rotation for Support Slimming</i>, &sect;I-A.";

void add_overhang_analysis_parameters(const MeshModel& m, RichParameterList& par) {
  add_print_parameters(m, par);
  par.addParam(RichBool("selectRisky", true, "Select risky faces",
                        "Replace the current face selection with the risky faces."));
  par.addParam(RichBool("colorize", true, "Colorize",
                        "Colour the faces by their quality on a fixed ramp: red (-1) is the worst overhang, "
                        "green (0) the threshold, blue (+1) safe."));
}

void apply_overhang_analysis(MeshDocument& md, const RichParameterList& par, FilterRun& run) {
  MeshModel& mm = current_triangle_mesh(md);
  const LayerView layer(mm.cm);
  // The rule reads the outside from the normals (see slimming.h): an inside-out mesh is analysed
  // turned over; faces that disagree are analysed as they are, with a warning.
  const slim::EdgeTopology edges = slim::edge_topology(layer.view.surface);
  const bool insideOut = slim::inside_out(layer.view.surface, edges);
  const slim::OverhangReport report = layer.run([&](const slim::Surface& s) {
    return slim::analyse_overhang(insideOut ? slim::flipped(s) : s, overhang_options(par));
  });

  // Only now that the analysis succeeded is the layer touched.
  const bool colorize = par.getBool("colorize");
  const bool select = par.getBool("selectRisky");
  mm.updateDataMask(MeshModel::MM_FACEQUALITY | (colorize ? int(MeshModel::MM_FACECOLOR) : 0));
  slim::vcgx::write_face_results(mm.cm, report.quality, colorize, select ? &report.risky : nullptr);

  run.info(QString::asprintf(
      "Overhang Analysis: %lld risky faces of %d; risky area %.6g mm^2 (%.2f%% of %.6g mm^2); "
      "%lld faces rest on the build plate",
      static_cast<long long>(report.risky_count), mm.cm.fn, report.risky_area, 100.0 * report.risky_share(),
      report.total_area, static_cast<long long>(report.plate_count)));
  if (insideOut) run.warning(QString("Overhang Analysis: ") + kInsideOutNotice);
  if (edges.flipped_edges > 0)
    run.warning(QString::asprintf(
        "Overhang Analysis: the faces are not consistently oriented (%s; %lld such edges), so some faces may be "
        "coloured as risky or safe wrongly; fix it with Filters > Normals, Curvatures and Orientation > Re-Orient "
        "all faces coherently",
        edges.first_flipped.c_str(), static_cast<long long>(edges.flipped_edges)));
  run.outputs["risky_area"] = report.risky_area;
  // int, not qlonglong: PyMeshLab hands back bool, int, float and arrays, and drops the rest.
  run.outputs["risky_faces"] = static_cast<int>(report.risky_count);
  run.outputs["total_area"] = report.total_area;
}

// ---- orientation, shared by Print Orientation and Support Slimming's "optimize the orientation first"

const char* const kSearchEffortHelp =
    "How many print directions the search tries: Fast (1000 directions over the sphere, 4 refined), Normal "
    "(4000, 8) or Thorough (16000, 16), besides the poses that rest a large flat face or a convex-hull facet "
    "on the plate.";

slim::OrientationOptions orientation_options(float alpha_max_deg, int effort) {
  const slim::OrientationEffort level = effort == 0   ? slim::OrientationEffort::Fast
                                        : effort == 2 ? slim::OrientationEffort::Thorough
                                                      : slim::OrientationEffort::Normal;
  slim::OrientationOptions o = slim::with_effort(level);
  o.alpha_max_deg = alpha_max_deg;
  return o;
}

// The search's findings for the log: the chosen pose, the proxy and risky area before and after,
// and the five best poses.
void log_orientation(const FilterRun& run, const QString& filter, const slim::OrientationResult& r, bool note_inside_out) {
  const slim::OrientationCandidate &best = r.best, &given = r.as_given;
  const double turn = std::acos(std::clamp(best.direction.z(), -1.0, 1.0)) * 180.0 / M_PI;
  run.info(filter + QString::asprintf(
                        ": print direction (%.4f, %.4f, %.4f) of the input, turned %.1f deg onto +Z; %d directions "
                        "searched in %.2f s",
                        best.direction.x(), best.direction.y(), best.direction.z(), turn, r.candidates, r.seconds));
  run.info(filter + QString::asprintf(
                        ": support proxy (shadow volume: risky faces' footprint x height above the plate) %.6g -> "
                        "%.6g mm^3; risky area %.6g -> %.6g mm^2; plate contact %.6g -> %.6g mm^2",
                        given.shadow_volume, best.shadow_volume, given.risky_area, best.risky_area,
                        given.contact_area, best.contact_area));
  run.info(filter + QString::asprintf(": best poses (score = proxy - %.3g mm x plate contact, lower is better):",
                                      r.contact_bonus_height));
  for (size_t k = 0; k < r.top.size() && k < 5; ++k) {
    const slim::OrientationCandidate& c = r.top[k];
    run.info(filter + QString::asprintf(
                          ":   %zu. score %.6g, proxy %.6g mm^3, risky area %.6g mm^2, contact %.6g mm^2, "
                          "direction (%.4f, %.4f, %.4f) [%s]",
                          k + 1, c.score, c.shadow_volume, c.risky_area, c.contact_area, c.direction.x(),
                          c.direction.y(), c.direction.z(), c.origin.c_str()));
  }
  run.info(filter + QString::asprintf(":   as given: score %.6g", given.score));
  if (r.inside_out && note_inside_out) run.warning(filter + ": " + kInsideOutNotice);
}

// ---- Print Orientation -----------------------------------------------------------------------

const char* const kPrintOrientationInfo =
    "Finds the print direction that needs the least support material, and turns the mesh into that pose: "
    "+Z up, resting on z = 0, as a <b>new layer</b> (the input layer is not changed).<br>"
    "Each direction is scored by a support estimate, the <b>shadow volume</b>: for every risky face "
    "(<i>n&middot;d + sin(&alpha;<sub>max</sub>) &lt; 0</i>, not resting on the plate), its area times "
    "<i>-n&middot;d</i> (its footprint) times the height of its centre above the plate, that is the volume "
    "of the support column under it. A small bonus for the area lying flat on the plate decides between "
    "poses that need no support. The search tries directions spread over the whole sphere, the poses that "
    "rest a large flat face or a convex-hull facet on the plate, and refines the best ones.<br>"
    "On the result, face quality and colour show the risky faces of the new pose, which are selected. "
    "The log lists the five best poses, and the risky area and the estimate before and after. Turning "
    "changes no shape; <i>Support Slimming</i> can then deform the part in its new pose.";

void add_print_orientation_parameters(const MeshModel&, RichParameterList& par) {
  add_alpha_max_parameter(par);
  par.addParam(RichEnum("searchEffort", 1, QStringList() << "Fast" << "Normal" << "Thorough", "Search effort",
                        kSearchEffortHelp));
  par.addParam(RichBool("applyResult", true, "Apply the result",
                        "Put the mesh in its best pose as a new layer '<name> oriented'. Off: only report the "
                        "best poses in the log."));
}

// Where a result layer's positions live. The filters read a layer's own coordinates, not its
// transformation matrix: a slimmed part stays in its input's frame, so it keeps the input's
// matrix and shows where the input shows; a part turned into its print pose is in the plate's
// frame, +Z up on z = 0, so it gets the identity.
enum class ResultFrame { Input, PrintPose };

// A copy of `input` as a new layer with the given positions and the overhang results of its pose;
// removed again if anything fails, so the document is never left half changed.
MeshModel* add_result_layer(MeshDocument& md, MeshModel& input, const QString& suffix, ResultFrame frame,
                            const slim::Points& V, const Eigen::VectorXd& face_quality, const std::vector<bool>& risky,
                            const Eigen::VectorXd* vertex_quality) {
  MeshModel* output = md.addNewMesh(QString(), input.label() + " " + suffix, true);
  try {
    output->updateDataMask(&input);
    vcg::tri::Append<CMeshO, CMeshO>::MeshCopy(output->cm, input.cm);
    if (frame == ResultFrame::Input) {
      output->cm.Tr = input.cm.Tr;
    } else {
      output->cm.Tr.SetIdentity();
    }
    output->updateDataMask(MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR |
                           (vertex_quality ? int(MeshModel::MM_VERTQUALITY) : 0));
    slim::vcgx::write_positions(output->cm, V);
    slim::vcgx::write_face_results(output->cm, face_quality, true, &risky);
    if (vertex_quality) slim::vcgx::write_vertex_quality(output->cm, *vertex_quality);
  } catch (...) {
    meshlab_api::delete_layer(md, output);
    md.setCurrentMesh(input.id());
    throw;
  }
  return output;
}

void apply_print_orientation(MeshDocument& md, const RichParameterList& par, FilterRun& run) {
  MeshModel& input = current_triangle_mesh(md);
  const LayerView layer(input.cm);
  const slim::OrientationResult r = layer.run([&](const slim::Surface& s) {
    return slim::optimize_orientation(s, orientation_options(par.getFloat("alphaMax"), par.getEnum("searchEffort")));
  });
  if (par.getBool("applyResult")) {
    const slim::Surface posed = slim::apply_orientation(layer.view.surface, r.rotation);
    const slim::OverhangReport report = slim::print_pose_overhang(posed, r, par.getFloat("alphaMax"));
    add_result_layer(md, input, "oriented", ResultFrame::PrintPose, layer.positions(posed.V), report.quality,
                     report.risky, nullptr);
  }
  log_orientation(run, "Print Orientation", r, true);
  run.outputs["shadow_volume_before"] = r.as_given.shadow_volume;
  run.outputs["shadow_volume_after"] = r.best.shadow_volume;
  run.outputs["risky_area_before"] = r.as_given.risky_area;
  run.outputs["risky_area_after"] = r.best.risky_area;
}

// ---- Support Slimming ------------------------------------------------------------------------

// Shown at the top of the dialog, always: short, so that every parameter fits below it on a
// 1280x1024 screen in MeshLab 2020.09. The details are in each parameter's help, which the
// dialog's Help button shows.
const char* const kSupportSlimmingInfo =
    "Deforms the mesh, as rigidly as possible, so that it needs less support material when printed "
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
                       "domain is made from these cells; finer follows smaller features but runs slower."));
  par.addParam(RichEnum("domain", 0, QStringList() << "Voxel" << "TetGen", "Domain",
                        "Voxel: tetrahedra from a voxel grid aligned with the print direction (works on open and "
                        "non-manifold meshes). TetGen: a constrained tetrahedralization of the surface; needs a "
                        "closed, clean, non-self-intersecting mesh."));
  par.addParam(RichEnum("method", 0, QStringList() << "Coherent" << "Paper", "Method",
                        "Each iteration turns every tetrahedron holding risky faces by the smallest rotation that "
                        "makes them self-supporting (an exact LP on the Gauss sphere; area-weighted K-means proxies "
                        "when no single rotation exists), then blends the tetrahedra back together with an "
                        "as-rigid-as-possible solve; the base stays on the build plate. Coherent (default): "
                        "neighbouring rotations agree, risky regions turn as a body, and flat overhangs turn towards "
                        "their nearest edge. Paper: <i>Direct Computation of Minimal Rotation for Support "
                        "Slimming</i> as written, for comparison."));
  par.addParam(RichInt("maxIterations", defaults.max_iterations, "Max iterations",
                       "The largest number of local/global iterations; the run ends sooner when the risky area "
                       "stops falling. 0 only embeds the mesh and writes it back."));
  par.addParam(RichFloat("maxDeviation", float(defaults.max_deviation_pct), "Deviation budget (%)",
                         "The farthest any vertex may move, as a percentage of the bounding box diagonal. It is a "
                         "constraint, not a stopping rule: the part of a step that would take a vertex further is "
                         "rolled back, and the run goes on. 0: no budget."));
  par.addParam(RichInt("maxK", defaults.max_k, "Max proxies per tetrahedron",
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

double bbox_diagonal(const slim::Surface& s) { return (s.V.colwise().maxCoeff() - s.V.colwise().minCoeff()).norm(); }

// The run's figures in the log, and every one of them in the outputs (slimming_figures.h's names;
// the first four keys are those of earlier releases, kept for scripts that read them).
void log_slimming(FilterRun& run, const slim::SlimmingResult& r, const slim::SlimmingFigures& f, bool orient) {
  const slim::IterationStats& chosen = r.history[static_cast<size_t>(r.iterations)];  // [0] is the input
  if (f.support_estimate_before_mm3 > 0.0)
    run.info(QString::asprintf("Support Slimming: support %.6g -> %.6g mm^3 (%+.1f%%; the support model's estimate of a "
                               "slicer's support%s)", f.support_estimate_before_mm3, f.support_estimate_after_mm3,
                               f.support_change_pct, orient ? ", in the print pose" : ""));
  run.info(QString::asprintf(
      "Support Slimming: risky area %.6g -> %.6g mm^2 (%.2f%% -> %.2f%% of the surface, %.1f%% less)",
      r.before.risky_area, r.after.risky_area, 100.0 * r.before.risky_share(), 100.0 * r.after.risky_share(),
      r.before.risky_area > 0 ? 100.0 * (1.0 - r.after.risky_area / r.before.risky_area) : 0.0));
  run.info(QString::asprintf("Support Slimming: %d iterations in %.2f s (%s); domain %d vertices, %d tets; solver %s",
                             r.iterations, r.seconds, r.stop_reason.c_str(), r.domain_vertices, r.domain_tets,
                             r.solver_backend.empty() ? "none (no iteration ran)" : r.solver_backend.c_str()));
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
  if (r.inside_out) run.warning(QString("Support Slimming: ") + kInsideOutNotice);
  for (const auto& [key, value] : slim::named_figures(f)) run.outputs[key] = value;
  run.outputs["risky_area_before"] = r.before.risky_area;
  run.outputs["risky_area_after"] = r.after.risky_area;
  run.outputs["iterations"] = r.iterations;  // a whole number, as before
  run.outputs["max_displacement"] = f.max_displacement_mm;
}

void apply_support_slimming(MeshDocument& md, const RichParameterList& par, FilterRun& run) {
  MeshModel& input = current_triangle_mesh(md);
  slim::SlimmingOptions options = slimming_options(par);
  if (par.getBool("preserveSelection")) {
    options.rigid_features = slim::vcgx::selected_faces(input.cm);
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
  const LayerView layer(input.cm);
  const bool orient = par.getBool("optimizeOrientation");
  const slim::OrientedSlimming job = layer.run([&](const slim::Surface& surface) {
    if (orient) return slim::slim_in_best_pose(surface, options, orientation_options(par.getFloat("alphaMax"), 1));
    slim::OrientedSlimming slimmed;
    slimmed.slimming = slim::slim_supports(surface, options);
    slimmed.posed = surface;
    return slimmed;
  });
  const slim::SlimmingResult& r = job.slimming;
  const slim::OrientationResult& orientation = job.orientation;
  const Eigen::VectorXd displacement = layer.view.to_input(r.displacement);
  add_result_layer(md, input, "slimmed", orient ? ResultFrame::PrintPose : ResultFrame::Input, layer.positions(r.surface.V),
                   r.after.quality, r.after.risky, &displacement);
  if (orient) log_orientation(run, "Support Slimming", orientation, false);  // slimming notes it below

  log_slimming(run, r, slim::slimming_figures(job.posed, r, bbox_diagonal(layer.view.surface)), orient);
}

}  // namespace

// ---- the table -------------------------------------------------------------------------------

const std::vector<FilterDefinition>& filter_definitions() {
  static const std::vector<FilterDefinition> filters = {
      {"Overhang Analysis", "compute_scalar_by_overhang_per_face", kOverhangAnalysisInfo, MenuCategory::Quality,
       MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR | MeshModel::MM_FACEFLAGSELECT,
       add_overhang_analysis_parameters, apply_overhang_analysis},
      {"Support Slimming", "generate_support_slimmed_mesh", kSupportSlimmingInfo, MenuCategory::Smoothing,
       MeshModel::MM_NONE,  // the result is a new layer; the input layer is left as it was
       add_support_slimming_parameters, apply_support_slimming},
      {"Print Orientation", "generate_print_oriented_mesh", kPrintOrientationInfo, MenuCategory::Normal,
       MeshModel::MM_NONE,  // the result is a new layer; the input layer is left as it was
       add_print_orientation_parameters, apply_print_orientation},
  };
  return filters;
}

const FilterDefinition* find_filter(int id) {
  const auto& filters = filter_definitions();
  return id >= 0 && id < static_cast<int>(filters.size()) ? &filters[static_cast<size_t>(id)] : nullptr;
}

QString filter_name(int id) {
  const FilterDefinition* f = find_filter(id);
  return f ? f->name : QString();
}

QString filter_info(int id) {
  const FilterDefinition* f = find_filter(id);
  return f ? f->info : QString();
}

QString filter_python_name(int id) {
  const FilterDefinition* f = find_filter(id);
  return f ? f->python_name : QString();
}

// ---- what every filter shares ----------------------------------------------------------------

RichParameterList default_parameters(const FilterDefinition& filter, const MeshModel& m) {
  RichParameterList par;
  filter.add_parameters(m, par);
  return par;
}

QString parameter_problem(const FilterDefinition& filter, const MeshDocument& md, const RichParameterList& par) {
  // A hand-written .mlx can drop a parameter, give it another type or an enum index out of range.
  // MeshLab's typed getters assert (abort the host) on a wrong type and throw on a missing name,
  // so everything is compared with our own list before any value is read.
  if (md.mm() == nullptr) return {};
  const RichParameterList expected = default_parameters(filter, *md.mm());
  for (const RichParameter& want : expected) {
    if (!par.hasParameter(want.name()))
      return QString("the parameter '%1' (%2) is missing; a script must list every parameter of the filter")
          .arg(want.name(), want.fieldDescription());
    const RichParameter& got = par.getParameterByName(want.name());
    if (!meshlab_api::same_parameter_type(got, want))
      return QString("the parameter '%1' (%2) is a %3, but it must be a %4")
          .arg(want.name(), want.fieldDescription(), got.stringType(), want.stringType());
    if (const auto* wantEnum = dynamic_cast<const RichEnum*>(&want)) {
      const int count = wantEnum->enumvalues.size();
      const int index = meshlab_api::enum_index(got);
      if (index < 0 || index >= count)
        return QString("the parameter '%1' (%2) is %3, but it must be one of 0..%4 (%5)")
            .arg(want.name(), want.fieldDescription())
            .arg(index)
            .arg(count - 1)
            .arg(wantEnum->enumvalues.join(", "));
    }
  }
  return {};
}

FilterOutcome run_filter(const FilterDefinition& filter, MeshDocument& md, const RichParameterList& par,
                         vcg::CallBackPos* progress, const LogLine& log) {
  FilterOutcome outcome;
  const auto fail = [&](const QString& reason) {
    outcome.failure = filter.name + ": " + reason;
    log(GLLogStream::WARNING, outcome.failure);
  };
  try {
    const QString problem = parameter_problem(filter, md, par);
    if (!problem.isEmpty()) {
      fail(problem);
      return outcome;
    }
    FilterRun run{log, progress, {}};
    filter.apply(md, par, run);
    outcome.outputs = std::move(run.outputs);
  } catch (const FilterFailure& e) {
    fail(e.reason);
  } catch (const slim::Cancelled&) {
    fail("cancelled; the document is unchanged");
  } catch (const std::exception& e) {
    fail(QString::fromUtf8(e.what()));
  } catch (...) {
    fail("unexpected internal error");
  }
  return outcome;
}

}  // namespace slim::plugin
