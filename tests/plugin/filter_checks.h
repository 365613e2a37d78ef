// What the plugin's filters must do to a MeshLab document, checked the same way whichever MeshLab
// API ran them: tests/plugin (2020.09) and tests/plugin_2022 (2022.02) compile this against their
// own MeshLab headers (meshlab_api.h of the API being built). GoogleTest EXPECTs; call from a TEST.
#pragma once

#include <vector>

#include <QString>
#include <QStringList>

#include "core/optimizer/slimming_options.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "meshlab_api.h"

namespace slim::test {

// Positions of a layer's vertices, in order.
std::vector<vcg::Point3f> positions(const MeshModel& m);

// Overhang Analysis's write-back on `m`: face quality as `expected`, the risky faces selected and
// only they, colours on the fixed ramp (clearly risky red-ish, clearly safe blue-ish).
void expect_overhang_written(const MeshModel& m, const OverhangReport& expected);

// Support Slimming's result: `out` is a new layer next to `input`, whose positions are still
// `original`; `out` has less risky area, face quality and selection as the core measures its
// shape, and vertex quality equal to each vertex's displacement; the filter's `log` reports the
// risky area and no inverted tetrahedron.
void expect_slimmed_layer(const MeshModel& input, const MeshModel& out, const std::vector<vcg::Point3f>& original,
                          double plate_tolerance, const QStringList& log);

// Print Orientation's result: `out` is a new layer "<input label> oriented" next to `input`, whose
// positions are still `original`; `out` has the same faces and holds the input in the core's best
// pose for `options` (+Z up, resting on z = 0); its face quality and selection describe that pose;
// the filter's `log` lists the top five poses and the proxy and risky area before and after.
void expect_oriented_layer(const MeshModel& input, const MeshModel& out, const std::vector<vcg::Point3f>& original,
                           const OrientationOptions& options, const QStringList& log);

// A deviation budget as the dialog's absolute-or-percentage parameter holds it: mm, its share of
// the bounding-box diagonal of the surface's finite vertices (0: none, or no finite vertex).
double dialog_budget_mm(const DeviationBudget& budget, const Surface& s);

// The parameters of `filter` in one of our examples/*.mlx, read by this MeshLab's script parser.
RichParameterList example_script_params(const QString& file, const QString& filter);

// A progress callback that cancels at its second report, as a host's cancel button would;
// progress_reports counts the calls (reset it before a run).
extern int progress_reports;
bool cancel_at_second_report(int percent, const char* message);

}  // namespace slim::test
