#include "filter_support_slimming.h"

#include <exception>

#include "core/overhang.h"
#include "vcg_adapters/surface_adapter.h"

namespace {

slim::OverhangOptions overhangOptions(const RichParameterList& par) {
  slim::OverhangOptions o;
  const auto d = par.getPoint3m("printDirection");
  o.print_direction = Eigen::Vector3d(d[0], d[1], d[2]);
  o.alpha_max_deg = par.getFloat("alphaMax");
  o.plate_tolerance = par.getAbsPerc("plateTolerance");
  return o;
}

}  // namespace

FilterSupportSlimming::FilterSupportSlimming() {
  typeList << FP_OVERHANG_ANALYSIS;
  for (FilterIDType id : types()) actionList << new QAction(filterName(id), this);
}

FilterSupportSlimming::~FilterSupportSlimming() = default;  // actions are children of this QObject

QString FilterSupportSlimming::pluginName() const { return "FilterSupportSlimming"; }

QString FilterSupportSlimming::filterName(FilterIDType filter) const {
  switch (filter) {
    case FP_OVERHANG_ANALYSIS: return "Overhang Analysis";
  }
  return {};
}

QString FilterSupportSlimming::filterInfo(FilterIDType filter) const {
  switch (filter) {
    case FP_OVERHANG_ANALYSIS:
      return "Finds the faces that would need support material when the mesh is 3D printed along the given "
             "<i>print direction</i>: a face is <b>risky</b> when <i>n&middot;d + sin(&alpha;<sub>max</sub>) &lt; 0</i>, "
             "that is, when it overhangs more than the self-supporting angle &alpha;<sub>max</sub> (measured from the "
             "vertical; 45&deg; is the usual rule). Faces lying on the build plate are carried by it and never count.<br>"
             "The geometry is not changed. Each face gets quality <i>n&middot;d + sin(&alpha;<sub>max</sub>)</i> "
             "(negative means risky; plate faces get +1), coloured on a fixed ramp from -1 (red) to +1 (blue) so that "
             "colours compare across meshes; the risky faces can be selected. The log reports the risky area.<br>"
             "From <i>Direct Computation of Minimal Rotation for Support Slimming</i>, &sect;I-A.";
  }
  return {};
}

MeshFilterInterface::FilterClass FilterSupportSlimming::getClass(QAction* action) {
  switch (ID(action)) {
    case FP_OVERHANG_ANALYSIS: return MeshFilterInterface::Quality;
  }
  return MeshFilterInterface::Quality;
}

MeshFilterInterface::FILTER_ARITY FilterSupportSlimming::filterArity(QAction*) const { return SINGLE_MESH; }

int FilterSupportSlimming::getPreConditions(QAction*) const { return MeshModel::MM_NONE; }

int FilterSupportSlimming::postCondition(QAction* action) const {
  switch (ID(action)) {
    case FP_OVERHANG_ANALYSIS:
      return MeshModel::MM_FACEQUALITY | MeshModel::MM_FACECOLOR | MeshModel::MM_FACEFLAGSELECT;
  }
  return MeshModel::MM_ALL;
}

void FilterSupportSlimming::initParameterSet(QAction* action, MeshModel& m, RichParameterList& par) {
  const float diag = m.cm.bbox.IsNull() ? 1.0f : m.cm.bbox.Diag();
  switch (ID(action)) {
    case FP_OVERHANG_ANALYSIS:
      par.addParam(RichPoint3f("printDirection", vcg::Point3f(0, 0, 1), "Print direction",
                               "The direction the part grows in while printing (the build plate's normal). "
                               "It need not be unit length."));
      par.addParam(RichFloat("alphaMax", 45.0f, "Self-supporting angle (deg)",
                             "The largest overhang, measured from the vertical, that prints without support. "
                             "Faces that lean out further are risky. Must be in [0, 90)."));
      par.addParam(RichAbsPerc("plateTolerance", 0.001f * diag, 0.0f, diag, "Build plate tolerance",
                               "Faces whose three vertices all lie within this distance of the lowest point along "
                               "the print direction rest on the build plate and are never risky."));
      par.addParam(RichBool("selectRisky", true, "Select risky faces",
                            "Replace the current face selection with the risky faces."));
      par.addParam(RichBool("colorize", true, "Colorize",
                            "Colour the faces by their quality on a fixed ramp: red (-1) is the worst overhang, "
                            "green (0) the threshold, blue (+1) safe."));
      break;
  }
}

bool FilterSupportSlimming::fail(const QString& reason) {
  errorMessage = reason;
  Log(GLLogStream::WARNING, "%s", qUtf8Printable(reason));
  return false;
}

bool FilterSupportSlimming::applyFilter(QAction* action, MeshDocument& md, const RichParameterList& par,
                                        vcg::CallBackPos*) {
  // Nothing may escape into MeshLab: an exception here would take the user's session down.
  try {
    switch (ID(action)) {
      case FP_OVERHANG_ANALYSIS: return applyOverhangAnalysis(md, par);
    }
    return fail("Unknown filter");
  } catch (const std::exception& e) {
    return fail(QString("%1: %2").arg(action->text(), e.what()));
  } catch (...) {
    return fail(QString("%1: unexpected internal error").arg(action->text()));
  }
}

bool FilterSupportSlimming::applyOverhangAnalysis(MeshDocument& md, const RichParameterList& par) {
  MeshModel* mm = md.mm();
  if (mm == nullptr) return fail("Overhang Analysis: there is no current mesh");
  if (mm->cm.fn == 0) return fail("Overhang Analysis: the mesh has no faces; it needs a triangle mesh, not a point cloud");

  const slim::Surface surface = slim::vcgx::to_surface(mm->cm);
  const slim::OverhangReport report = slim::analyse_overhang(surface, overhangOptions(par));

  // Only now that the analysis succeeded is the layer touched.
  const bool colorize = par.getBool("colorize");
  const bool select = par.getBool("selectRisky");
  mm->updateDataMask(MeshModel::MM_FACEQUALITY | (colorize ? int(MeshModel::MM_FACECOLOR) : 0));
  slim::vcgx::write_face_results(mm->cm, report.quality, colorize, select ? &report.risky : nullptr);

  Log("Overhang Analysis: %lld risky faces of %d; risky area %.6g mm^2 (%.2f%% of %.6g mm^2); "
      "%lld faces rest on the build plate",
      static_cast<long long>(report.risky_count), mm->cm.fn, report.risky_area, 100.0 * report.risky_share(),
      report.total_area, static_cast<long long>(report.plate_count));
  return true;
}
