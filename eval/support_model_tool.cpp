// support_model_tool: the support model's validation steps (eval/studies/support-model.sh), one
// subcommand each; "key=value" lines on stdout, a one-line reason and exit 1 on bad input.
//
//   support_model_tool estimate MESH [--angle DEG] [--phases N] [--turns N] [--pixels N] [--layers]
//                                    [--open-slices 0|1] [--slice-gap MM]
//       The model's estimate for MESH as printed in its own frame (+Z up), part by part (and with
//       --layers, layer by layer: "layer J MM3"), and the mesh's open and non-manifold edges;
//       --open-slices 0 reads an open mesh along rays, as the model did before it sliced them.
//   support_model_tool turn MESH DEG OUT.stl
//       MESH turned by DEG about +Z through its bounding-box centre, resting on z = 0, as STL:
//       the same part against another grid angle and phase.
//   support_model_tool gcode FILE.gcode
//       The support filament of a PrusaSlicer or CuraEngine G-code file (its "Support material",
//       "Support material interface", "SUPPORT" and "SUPPORT-INTERFACE" sections), in mm³.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include <Eigen/Geometry>

#include "core/support_model/support_model.h"
#include "gcode_extrusion.h"
#include "mesh_io/mesh_io.h"

namespace {

int estimate(int argc, char** argv) {
  slim::SupportModelOptions o;
  bool layers = false;
  for (int i = 3; i < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--layers") {
      layers = true;
      --i;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(k + " needs a value");
    const char* v = argv[i + 1];
    if (k == "--angle") o.print.alpha_max_deg = std::atof(v);
    else if (k == "--phases") o.grid_phases = std::atoi(v);
    else if (k == "--turns") o.turns = std::atoi(v);
    else if (k == "--pixels") o.pixels_per_cell = std::atoi(v);
    else if (k == "--creases") o.bottom_creases = std::atoi(v) != 0;
    else if (k == "--tips") o.lowest_points = std::atoi(v) != 0;
    else if (k == "--open-slices") o.open_mesh_slices = std::atoi(v) != 0;
    else if (k == "--slice-gap") o.slice_max_gap = std::atof(v);
    else throw std::invalid_argument("unknown option " + k);
  }
  const slim::Surface surface = slim::io::load_surface(argv[2]);
  const slim::SupportEstimate e = slim::estimate_support(surface, o);
  const slim::EdgeTopology edges = slim::edge_topology(surface);
  std::printf("open_edges=%lld\nnonmanifold_edges=%lld\n", static_cast<long long>(edges.open_edges),
              static_cast<long long>(edges.nonmanifold_edges));
  std::printf("volume_mm3=%.3f\nbase_fill_mm3=%.3f\nsheath_mm3=%.3f\ntop_interface_mm3=%.3f\n"
              "bottom_interface_mm3=%.3f\nfirst_layer_mm3=%.3f\nmin_phase_mm3=%.3f\nmax_phase_mm3=%.3f\n"
              "contact_area_mm2=%.3f\nlanding_area_mm2=%.3f\ncolumn_volume_mm3=%.3f\npixel_mm=%.4f\nlayers=%d\ncells=%d\n",
              e.volume_mm3, e.base_fill_mm3, e.sheath_mm3, e.top_interface_mm3, e.bottom_interface_mm3, e.first_layer_mm3,
              e.min_phase_mm3, e.max_phase_mm3, e.contact_area_mm2, e.landing_area_mm2, e.column_volume_mm3, e.pixel_mm,
              e.layers, e.cells);
  if (layers) {
    for (size_t j = 0; j < e.layer_mm3.size(); ++j) std::printf("layer %zu %.4f\n", j, e.layer_mm3[j]);
  }
  return 0;
}

int turn(char** argv) {
  slim::Surface s = slim::io::load_surface(argv[2]);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(std::atof(argv[3]) * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::RowVector3d centre = 0.5 * (s.V.colwise().minCoeff() + s.V.colwise().maxCoeff());
  s.V = (s.V.rowwise() - centre) * r.transpose();
  s.V.col(2).array() -= s.V.col(2).minCoeff();
  slim::io::save_surface(argv[4], s);
  return 0;
}

int gcode(char** argv) {
  std::ifstream in(argv[2]);
  if (!in) throw std::invalid_argument(std::string("cannot read ") + argv[2]);
  const slim::eval::GcodeExtrusion g = slim::eval::measure_extrusion(in);
  double mm = 0.0;
  for (const char* type : {"Support material", "Support material interface", "SUPPORT", "SUPPORT-INTERFACE"})
    mm += g.type_mm(type);
  std::printf("support_mm3=%.3f\n", mm * slim::eval::filament_area(g.filament_diameter().value_or(1.75)));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  try {
    if (cmd == "estimate" && argc >= 3) return estimate(argc, argv);
    if (cmd == "turn" && argc == 5) return turn(argv);
    if (cmd == "gcode" && argc == 3) return gcode(argv);
  } catch (const std::exception& e) {
    std::cerr << "support_model_tool: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: support_model_tool estimate MESH [--angle DEG] [--phases N] [--turns N] [--pixels N] [--layers]\n"
               "       support_model_tool turn MESH DEG OUT.stl\n"
               "       support_model_tool gcode FILE.gcode\n";
  return 1;
}
