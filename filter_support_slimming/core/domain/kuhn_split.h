// The Kuhn split of a cube into 6 tets, the same in every cell of the voxel grid, so that
// neighbouring cells share their face triangles and the tet mesh is conforming.
//
// In local coordinates x = g - (i, j, k) of cell (i, j, k) (each in [0, 1]), Kuhn tet p (0..5) is
// the region 1 >= x_a >= x_b >= x_c >= 0, (a, b, c) = the p-th permutation of (0, 1, 2) in
// lexicographic order: the 6 tets around the cell's main diagonal, node (0,0,0) to (1,1,1).
//
//   kuhn_corners(p)          its 4 corners as cube corners (bit 0: +1 along e1, bit 1: +1 along
//                            e2, bit 2: +1 along d), in TetMesh::T order (positive volume).
//   kuhn_barycentric(p, x)   the barycentric coordinates (T order) of local point x: exact
//                            telescoping differences of x, so they sum to 1 to rounding.
//   kuhn_planes(cell, p)     its planes in grid coordinates g: w[m]·g + o[m] is the barycentric
//                            coordinate of corner m (>= 0 inside). The tet sharing a face computes
//                            exactly the negated value there (small-integer offsets, exact), which
//                            is what makes clipping against neighbouring tets consistent.
#pragma once

#include <array>

#include <Eigen/Core>

namespace slim {

struct TetPlanes {
  std::array<Eigen::Vector3d, 4> w;
  std::array<double, 4> o;
};

const std::array<int, 4>& kuhn_corners(int p);
Eigen::Vector4d kuhn_barycentric(int p, const Eigen::Vector3d& x);
TetPlanes kuhn_planes(const Eigen::Vector3i& cell, int p);

}  // namespace slim
