// The voxel grid of the tet domain (voxel_domain.h): a regular grid of cubes in a frame aligned
// with the print direction.
//
// VoxelGrid: cell (i, j, k) is the cube [i, i+1] x [j, j+1] x [k, k+1] in grid coordinates (cell
// units), with 0 <= i < cells(0) etc. Grid coordinates of a world point x: (axes x - low) / h.
//   axes       3 by 3, rows e1, e2, d: the world -> frame rotation (print_frame)
//   low        frame coordinates of node (0, 0, 0), mm
//   cell_size  h, mm
//   cells      number of cells along e1, e2, d
//
// print_frame(d): rows e1, e2, d for a unit print direction d, chosen from d alone so that the
// same d always gives the same grid. e1 is the world axis least aligned with d (the lowest index
// on ties) made orthogonal to d; e2 = d x e1; d = +Z gives the identity.
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace slim {

struct VoxelGrid {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d low = Eigen::Vector3d::Zero();
  double cell_size = 1.0;
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();

  Eigen::Vector3d to_grid(const Eigen::Vector3d& x) const { return (axes * x - low) / cell_size; }
  Eigen::Vector3d to_world(const Eigen::Vector3d& g) const {
    return axes.transpose() * (low + cell_size * g);
  }
  std::int64_t cell_count() const {
    return static_cast<std::int64_t>(cells(0)) * cells(1) * cells(2);
  }
  std::int64_t cell_index(int i, int j, int k) const {
    return i + static_cast<std::int64_t>(cells(0)) * (j + static_cast<std::int64_t>(cells(1)) * k);
  }
};

Eigen::Matrix3d print_frame(const Eigen::Vector3d& d);

}  // namespace slim
