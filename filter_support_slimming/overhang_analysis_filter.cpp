#include "filter_parts.h"

#include <algorithm>
#include <cmath>

#include "core/optimizer/slimming_figures.h"
#include "core/orientation/oriented_slimming.h"

namespace slim::plugin {

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
  const LayerView layer(md);
  MeshModel& mm = layer.model;
  // The rule reads the outside from the normals (see slimming.h): an inside-out mesh is analysed
  // turned over; faces that disagree are analysed as they are, with a warning.
  const slim::EdgeTopology edges = slim::edge_topology(layer.view.surface);
  const bool insideOut = slim::inside_out(layer.view.surface, edges);
  const slim::OverhangReport report = layer.run([&](const slim::Surface& s) {
    return slim::analyse_overhang(insideOut ? slim::flipped(s) : s, print_setup(par));
  });

  // Only now that the analysis succeeded is the layer touched.
  const bool colorize = par.getBool("colorize");
  const bool select = par.getBool("selectRisky");
  mm.updateDataMask(MeshModel::MM_FACEQUALITY | (colorize ? int(MeshModel::MM_FACECOLOR) : 0));
  slim::vcg_adapters::write_face_results(mm.cm, report.quality, colorize, select ? &report.risky : nullptr);

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

}  // namespace slim::plugin
