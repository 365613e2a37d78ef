// A tetrahedral mesh: the computation domain T of the paper (§II).
//
// TetMesh::V  #V by 3 vertex positions, in the surface's units.
// TetMesh::T  #T by 4 vertex indices, ordered so that every tet has positive volume:
//             (v1 - v0) . ((v2 - v0) x (v3 - v0)) > 0.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/geometry/surface.h"

namespace slim {

using Tets = Eigen::Matrix<int, Eigen::Dynamic, 4>;  // #T by 4

struct TetMesh {
  Points V;
  Tets T;
};

// Signed volume of tet t (positive for the orientation above).
inline double tet_volume(const Points& V, const Eigen::Matrix<int, 1, 4>& t) {
  const Eigen::Vector3d a = V.row(t(0)).transpose();
  const Eigen::Vector3d e1 = V.row(t(1)).transpose() - a;
  const Eigen::Vector3d e2 = V.row(t(2)).transpose() - a;
  const Eigen::Vector3d e3 = V.row(t(3)).transpose() - a;
  return e1.dot(e2.cross(e3)) / 6.0;
}

}  // namespace slim
