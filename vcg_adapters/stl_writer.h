// Binary STL written through VCG's exporter: what mesh_io.h's write_mesh does for .stl.
//
//   write_stl(path, surface, face_quality);
//
// In: the surface (#V by 3 mm, #F by 3) and, optionally, #F face qualities (empty: none). Out: a
// binary STL at `path` with facet normals recomputed from the positions; with face qualities,
// each facet's attribute bytes carry its colour on the fixed quality ramp (quality_ramp.h), as
// VCG (and so MeshLab) writes facet colours. Throws std::runtime_error naming the path and VCG's
// reason when the file cannot be written.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim::vcg_adapters {

void write_stl(const std::string& path, const Surface& surface, const Eigen::VectorXd& face_quality);

}  // namespace slim::vcg_adapters
