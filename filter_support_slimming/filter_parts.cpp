#include "filter_parts.h"

#include <optional>

#include <QRegularExpression>
#include <vcg/complex/append.h>

#include "vcg_adapters/displacement_ramp.h"

namespace slim::plugin {

void add_alpha_max_parameter(RichParameterList& par) {
  par.addParam(RichFloat("alphaMax", 45.0f, "Self-supporting angle (deg)",
                         "Largest overhang from the vertical that prints without support; in [0, 90)."));
}

float dialog_diagonal(const MeshModel& m) { return m.cm.bbox.IsNull() ? 1.0f : m.cm.bbox.Diag(); }

void add_print_parameters(const MeshModel& m, RichParameterList& par) {
  const float diag = dialog_diagonal(m);
  par.addParam(meshlab_api::RichDirection(
      "printDirection", vcg::Point3f(0, 0, 1), "Print direction",
      "The direction the part grows in (the build plate's normal); any length."));
  add_alpha_max_parameter(par);
  par.addParam(meshlab_api::RichAbsPerc("plateTolerance", 0.001f * diag, 0.0f, diag,
                                         "Build plate tolerance",
                                         "Faces this close to the lowest point rest on the plate, never risky."));
}

slim::PrintSetup print_setup(const RichParameterList& par) {
  slim::PrintSetup o;
  const auto d = par.getPoint3m("printDirection");
  o.direction = Eigen::Vector3d(d[0], d[1], d[2]);
  o.alpha_max_deg = par.getFloat("alphaMax");
  o.plate = slim::PlateRule::within(par.getAbsPerc("plateTolerance"));
  return o;
}

// The filter's parameters -> the core's options. Ranges are checked by the core, which says what
// is wrong in words the log can show; here what the core would read otherwise: a negative budget
// or crease limit (the core reads 0 as none) and the least saving, checked before any work.
slim::SlimmingOptions slimming_options(const RichParameterList& par) {
  slim::SlimmingOptions o;
  o.print = print_setup(par);
  o.resolution = par.getInt("resolution");
  o.domain = par.getEnum("domain") == 1 ? slim::DomainKind::TetGen : slim::DomainKind::Voxel;
  o.method = par.getEnum("method") == 1 ? slim::SlimmingMethod::Paper : slim::SlimmingMethod::Coherent;
  o.steps.max_iterations = par.getInt("maxIterations");
  const double budget = par.getAbsPerc("maxDeviation");  // mm (the dialog's percentage is of the bbox diagonal)
  if (budget < 0.0)  // a typo's minus sign must not turn the budget off (NaN: the core says "finite")
    throw FilterFailure(QString("the deviation budget must be >= 0 mm (0: no budget), got %1").arg(budget));
  o.budget = budget == 0.0 ? slim::DeviationBudget::none() : slim::DeviationBudget::length(budget);
  const double creases = par.getFloat("maxCreases");
  if (!(creases >= 0.0 && creases <= 100.0))
    throw FilterFailure(QString("the crease limit must be in [0, 100] % (0: no limit), got %1").arg(creases));
  o.result.max_crease_share_pct = creases == 0.0 ? std::nullopt : std::optional<double>(creases);
  const double saving = par.getFloat("minSaving");
  if (!(saving >= 0.0 && saving < 100.0))
    throw FilterFailure(QString("the least saving must be in [0, 100) % (0: any saving), got %1").arg(saving));
  o.result.min_support_saving_pct = saving;
  o.steps.max_k = par.getInt("maxK");
  if (par.getBool("allowStretch")) slim::allow_stretch(o);
  return o;
}

// The current layer, refused when there is none or it is a point cloud.
MeshModel& current_triangle_mesh(MeshDocument& md) {
  MeshModel* m = md.mm();
  if (m == nullptr) throw FilterFailure("there is no current mesh");
  if (m->cm.fn == 0) throw FilterFailure("the mesh has no faces; it needs a triangle mesh, not a point cloud");
  return *m;
}

const char* const kInsideOutNotice =
    "the mesh is inside out (closed, with every normal pointing inwards): it was analysed with its faces turned "
    "over; to fix the layer itself use Filters > Normals, Curvatures and Orientation > Invert Faces Orientation";

const char* const kSearchEffortHelp =
    "How hard the search tries: Fast (1000 directions over the sphere, 4 refined, 32 poses judged by the "
    "support model), Normal (4000, 8, 64) or Thorough (16000, 16, 128).";

slim::OrientationOptions orientation_options(float alpha_max_deg, int effort) {
  const slim::OrientationEffort level = effort == 0   ? slim::OrientationEffort::Fast
                                        : effort == 2 ? slim::OrientationEffort::Thorough
                                                      : slim::OrientationEffort::Normal;
  slim::OrientationOptions o = slim::with_effort(level);
  o.alpha_max_deg = alpha_max_deg;
  return o;
}

void log_orientation(const FilterRun& run, const QString& filter, const slim::OrientationResult& r, bool note_inside_out) {
  const slim::OrientationCandidate &best = r.best, &given = r.as_given;
  const double turn = std::acos(std::clamp(best.direction.z(), -1.0, 1.0)) * 180.0 / M_PI;
  run.info(filter + QString::asprintf(
                        ": print direction (%.4f, %.4f, %.4f) of the input, turned %.1f deg onto +Z; %d directions "
                        "searched in %.2f s",
                        best.direction.x(), best.direction.y(), best.direction.z(), turn, r.candidates, r.seconds));
  if (given.support_estimate && best.support_estimate)
    run.info(filter + QString::asprintf(": support %.6g -> %.6g mm^3 (the support model's estimate of a slicer's "
                                        "support, which chose the pose)",
                                        *given.support_estimate, *best.support_estimate));
  run.info(filter + QString::asprintf(
                        ": support proxy (shadow volume: risky faces' footprint x height above the plate) %.6g -> "
                        "%.6g mm^3; risky area %.6g -> %.6g mm^2; plate contact %.6g -> %.6g mm^2",
                        given.shadow_volume, best.shadow_volume, given.risky_area, best.risky_area,
                        given.contact_area, best.contact_area));
  run.info(filter + QString::asprintf(": best poses, the chosen first, then by the support model's estimate (lower is "
                                      "better; %d poses judged at one grid phase, %d in full):",
                                      r.judged_coarse, r.judged_fine));
  auto support = [](const slim::OrientationCandidate& c) { return c.support_estimate ? *c.support_estimate : NAN; };
  for (size_t k = 0; k < r.top.size() && k < 5; ++k) {
    const slim::OrientationCandidate& c = r.top[k];
    run.info(filter + QString::asprintf(
                          ":   %zu. support %.6g mm^3, %s on the plate, contact %.6g mm^2, proxy %.6g mm^3, "
                          "direction (%.4f, %.4f, %.4f) [%s]",
                          k + 1, support(c), c.stable ? "stands" : "balances", c.contact_area, c.shadow_volume,
                          c.direction.x(), c.direction.y(), c.direction.z(), c.origin.c_str()));
  }
  run.info(filter + QString::asprintf(":   as given: support %.6g mm^3, %s on the plate, proxy %.6g mm^3", support(given),
                                      given.stable ? "stands" : "balances", given.shadow_volume));
  if (r.inside_out && note_inside_out) run.warning(filter + ": " + kInsideOutNotice);
}

QString result_layer_name(const QString& input_label, const QString& suffix) {
  QString name = input_label;
  name.remove(QRegularExpression("\\.[A-Za-z0-9]{2,4}$"));
  return name + "_" + suffix;
}

namespace {

// Vertex quality = the displacement; vertex colour = its ramp, unless the input has colours.
void write_displacement(MeshModel& output, const MeshModel& input, const Displacement& d) {
  output.updateDataMask(MeshModel::MM_VERTQUALITY);
  slim::vcg_adapters::write_vertex_quality(output.cm, d.per_vertex);
  if (input.hasDataMask(MeshModel::MM_VERTCOLOR)) return;  // the input's own colours, as they were
  output.updateDataMask(MeshModel::MM_VERTCOLOR);
  for (CVertexO& v : output.cm.vert)
    if (!v.IsD()) {
      const Eigen::Matrix<unsigned char, 1, 4> c = slim::vcg_adapters::displacement_ramp_colour(v.Q(), d.ramp_top_mm);
      v.C() = vcg::Color4b(c(0), c(1), c(2), c(3));
    }
}

}  // namespace

// A copy of `input` as a new layer with the given positions and the overhang results of its pose;
// removed again if anything fails, so the document is never left half changed.
MeshModel* add_result_layer(MeshDocument& md, MeshModel& input, const QString& suffix, ResultFrame frame,
                            const slim::Points& V, const Eigen::VectorXd& face_quality, const std::vector<bool>& risky,
                            const Displacement* displacement) {
  MeshModel* output = md.addNewMesh(QString(), result_layer_name(input.label(), suffix), true);
  try {
    output->updateDataMask(&input);
    vcg::tri::Append<CMeshO, CMeshO>::MeshCopy(output->cm, input.cm);
    if (frame == ResultFrame::Input) {
      output->cm.Tr = input.cm.Tr;
    } else {
      output->cm.Tr.SetIdentity();
    }
    output->updateDataMask(MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR);
    slim::vcg_adapters::write_positions(output->cm, V);
    slim::vcg_adapters::write_face_results(output->cm, face_quality, true, &risky);
    if (displacement) write_displacement(*output, input, *displacement);
  } catch (...) {
    meshlab_api::delete_layer(md, output);
    md.setCurrentMesh(input.id());
    throw;
  }
  return output;
}

}  // namespace slim::plugin
