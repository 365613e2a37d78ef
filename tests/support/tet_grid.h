// A structured box of tetrahedra for tests and benchmarks only (the real domain is
// core/domain/voxel_domain.h). Every cube is split into the 6 Kuhn tets along its 000-111 diagonal;
// all cubes use the same split, so neighbouring cubes share faces exactly (a conforming mesh).
#pragma once

#include <vector>

#include "core/geometry/tet_mesh.h"

namespace slim::test {

// nx by ny by nz cubes of side h, the lowest corner at `origin`.
//   V  (nx+1)(ny+1)(nz+1) by 3, index i + (nx+1) * (j + (ny+1) * k) for grid point (i, j, k)
//   T  6 nx ny nz by 4, every tet with volume h^3 / 6 > 0
// Throws std::invalid_argument for a non-positive count or side.
TetMesh tet_grid(int nx, int ny, int nz, double h = 1.0,
                 const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

// The grid's vertices with z == origin.z(): the layer resting on the build plate.
std::vector<int> grid_bottom_vertices(int nx, int ny);

}  // namespace slim::test
