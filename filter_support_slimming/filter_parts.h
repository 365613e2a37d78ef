// What the plugin's three filters share, and each filter's parts for filters.h's table.
//
// Shared: the dialog's print parameters and their translation into the core's options, the current
// layer as the core sees it (LayerView: live elements in order, coincident vertices merged), the
// orientation search's options and log, and the result layer (a copy of the input with new
// positions and the overhang results of its pose). Each filter lives in a file of its own name:
// overhang_analysis_filter.cpp, print_orientation_filter.cpp, support_slimming_filter.cpp.
#pragma once

#include <stdexcept>
#include <vector>

#include <QString>

#include "core/geometry/welded_view.h"
#include "core/optimizer/slimming.h"
#include "core/orientation/orientation.h"
#include "core/print/overhang.h"
#include "filters.h"
#include "vcg_adapters/surface_adapter.h"

namespace slim::plugin {

// Each filter's help (the top of its dialog), parameters and run, in the file of its name; the
// table in filters.cpp puts them together.
extern const char* const kOverhangAnalysisInfo;
void add_overhang_analysis_parameters(const MeshModel& m, RichParameterList& par);
void apply_overhang_analysis(MeshDocument& md, const RichParameterList& par, FilterRun& run);
extern const char* const kSupportSlimmingInfo;
void add_support_slimming_parameters(const MeshModel& m, RichParameterList& par);
void apply_support_slimming(MeshDocument& md, const RichParameterList& par, FilterRun& run);
extern const char* const kPrintOrientationInfo;
void add_print_orientation_parameters(const MeshModel& m, RichParameterList& par);
void apply_print_orientation(MeshDocument& md, const RichParameterList& par, FilterRun& run);

// ---- parameters shared by the filters
// The length MeshLab's absolute-or-percentage parameters take their percentage of: m's bounding-box
// diagonal (1 for an empty mesh).
float dialog_diagonal(const MeshModel& m);
void add_alpha_max_parameter(RichParameterList& par);
// Print direction, alpha_max and the build plate tolerance (fitted to m's size).
void add_print_parameters(const MeshModel& m, RichParameterList& par);
slim::PrintSetup print_setup(const RichParameterList& par);
// The filter's parameters -> the core's options. Ranges are checked by the core, which says what
// is wrong in words the log can show.
slim::SlimmingOptions slimming_options(const RichParameterList& par);

// The current layer, refused (FilterFailure) when there is none or it is a point cloud.
MeshModel& current_triangle_mesh(MeshDocument& md);

// The layer as the core sees it: its live vertices and faces in container order, coincident
// vertices merged (core/geometry/welded_view.h), so that faces meeting at a seam share their vertex.
// Results come back to every vertex of the layer, whose list and order never change.
struct LayerView {
  MeshModel& model;       // md's current layer, a triangle mesh (current_triangle_mesh)
  slim::Surface surface;  // the layer's own vertex and face lists
  slim::WeldedView view;
  explicit LayerView(MeshDocument& md)
      : model(current_triangle_mesh(md)), surface(slim::vcg_adapters::to_surface(model.cm)), view(slim::weld_coincident(surface)) {}
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

// Logged by the filters when the mesh is inside out (slim::inside_out).
extern const char* const kInsideOutNotice;

// ---- orientation, shared by Print Orientation and Support Slimming's "optimize the orientation first"
extern const char* const kSearchEffortHelp;
// The search's options for an effort index of the dialog (0 Fast, 1 Normal, 2 Thorough).
slim::OrientationOptions orientation_options(float alpha_max_deg, int effort);
// The search's findings for the log: the chosen pose, the proxy and risky area before and after,
// and the five best poses.
void log_orientation(const FilterRun& run, const QString& filter, const slim::OrientationResult& r, bool note_inside_out);

// Where a result layer's positions live. The filters read a layer's own coordinates, not its
// transformation matrix: a slimmed part stays in its input's frame, so it keeps the input's
// matrix and shows where the input shows; a part turned into its print pose is in the plate's
// frame, +Z up on z = 0, so it gets the identity.
enum class ResultFrame { Input, PrintPose };

// "<name>_<suffix>": the input layer's name without its file extension ("bunny.ply" ->
// "bunny_slimmed"), so every MeshLab shows it whole (2020.09's layer list cuts at the last dot).
QString result_layer_name(const QString& input_label, const QString& suffix);

// How far each vertex of the layer moved (mm), for the result's vertex quality, and the length the
// colour ramp reaches red at (the deviation budget in mm, or the largest displacement without one).
struct Displacement {
  Eigen::VectorXd per_vertex;
  double ramp_top_mm = 0.0;
};

// A copy of `input` as a new layer named result_layer_name(input's label, suffix), with the given
// positions and the overhang results of its pose; removed again if anything fails, so the
// document is never left half changed. With a displacement, vertex quality is that displacement
// and, when the input has no vertex colours of its own, the vertex colours are VCG's colour ramp of
// it, blue where a vertex did not move to red at ramp_top_mm and beyond; MeshLab then draws the
// layer with them. Input vertex colours pass through untouched.
MeshModel* add_result_layer(MeshDocument& md, MeshModel& input, const QString& suffix, ResultFrame frame,
                            const slim::Points& V, const Eigen::VectorXd& face_quality, const std::vector<bool>& risky,
                            const Displacement* displacement);

}  // namespace slim::plugin
