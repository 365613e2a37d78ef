#include "filter_parts.h"

#include <algorithm>
#include <cmath>

#include "core/optimizer/slimming_figures.h"
#include "core/orientation/oriented_slimming.h"

namespace slim::plugin {

const char* const kPrintOrientationInfo =
    "Finds the print direction that needs the least support material, and turns the mesh into that pose: "
    "+Z up, resting on z = 0, as a <b>new layer</b> (the input layer is not changed).<br>"
    "The search scores directions over the whole sphere by a quick proxy (the <b>shadow volume</b>: each "
    "overhanging face's footprint times its height above the plate), refines the best, and then lets the "
    "<b>support model</b> (what a slicer builds) judge them together with the poses you would try: resting on a "
    "large flat face or a convex-hull facet, along the principal axes, on the largest clusters of faces. The "
    "least support wins; within 5% of it, a pose that stands on the plate by itself beats one balanced on a "
    "point or an edge.<br>"
    "On the result, face quality and colour show the risky faces of the new pose, which are selected. "
    "The log lists the five best poses by the model, and the risky area and the estimate before and after. Turning "
    "changes no shape; <i>Support Slimming</i> can then deform the part in its new pose.";

void add_print_orientation_parameters(const MeshModel&, RichParameterList& par) {
  add_alpha_max_parameter(par);
  par.addParam(RichEnum("searchEffort", 1, QStringList() << "Fast" << "Normal" << "Thorough", "Search effort",
                        kSearchEffortHelp));
  par.addParam(RichBool("applyResult", true, "Apply the result",
                        "Put the mesh in its best pose as a new layer '<name> oriented'. Off: only report the "
                        "best poses in the log."));
}

void apply_print_orientation(MeshDocument& md, const RichParameterList& par, FilterRun& run) {
  const LayerView layer(md);
  const slim::OrientationResult r = layer.run([&](const slim::Surface& s) {
    return slim::optimize_orientation(s, orientation_options(par.getFloat("alphaMax"), par.getEnum("searchEffort")));
  });
  if (par.getBool("applyResult")) {
    const slim::Surface posed = slim::apply_orientation(layer.view.surface, r.rotation);
    const slim::OverhangReport report = slim::print_pose_overhang(posed, r, par.getFloat("alphaMax"));
    add_result_layer(md, layer.model, "oriented", ResultFrame::PrintPose, layer.positions(posed.V), report.quality,
                     report.risky, nullptr);
  }
  log_orientation(run, "Print Orientation", r, true);
  run.outputs["shadow_volume_before"] = r.as_given.shadow_volume;
  run.outputs["shadow_volume_after"] = r.best.shadow_volume;
  run.outputs["risky_area_before"] = r.as_given.risky_area;
  run.outputs["risky_area_after"] = r.best.risky_area;
  // The outputs are numbers: -1 where the support model did not judge the pose.
  run.outputs["support_estimate_before_mm3"] = r.as_given.support_estimate.value_or(-1.0);
  run.outputs["support_estimate_after_mm3"] = r.best.support_estimate.value_or(-1.0);
}

}  // namespace slim::plugin
