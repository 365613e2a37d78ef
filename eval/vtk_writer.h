// Legacy VTK files (ASCII "# vtk DataFile Version 3.0", POLYDATA) for the report's pictures:
// f3d colours them by a named scalar array and draws its colour bar (--scalars NAME --bar).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim::eval {

// A triangle mesh with one scalar per vertex (point data named `name`, #V values).
// Throws std::runtime_error when the file cannot be written or the sizes disagree.
void write_vtk_mesh(const std::string& path, const Surface& s, const std::string& name, const Eigen::VectorXd& per_vertex);

// Line segments with one scalar per segment (cell data named `name`).
struct Segments {
  std::vector<Eigen::Vector3d> from, to;
  std::vector<double> value;
};
void write_vtk_segments(const std::string& path, const Segments& segments, const std::string& name);

}  // namespace slim::eval
