#include "core/domain/kuhn_split.h"

#include <algorithm>

namespace slim {

namespace {

struct KuhnTables {
  std::array<std::array<int, 3>, 6> order;    // (a, b, c): 1 >= x_a >= x_b >= x_c >= 0
  std::array<std::array<int, 4>, 6> corners;  // in T order
  std::array<std::array<int, 4>, 6> slot;     // slot[p][m]: T column of path corner m
  // Barycentric coordinate of T corner m as w·x + base, x the cell's local coordinates.
  std::array<TetPlanes, 6> local;
  KuhnTables() {
    std::array<int, 3> perm{0, 1, 2};
    for (size_t p = 0; p < 6; ++p) {
      order[p] = perm;
      // The path from corner 0 to corner 7: +e_a, then +e_b, then +e_c.
      const std::array<int, 4> path{0, 1 << perm[0], (1 << perm[0]) | (1 << perm[1]), 7};
      // Its volume is the sign of the permutation; odd ones swap corners 1 and 2.
      const int inversions = (perm[0] > perm[1]) + (perm[0] > perm[2]) + (perm[1] > perm[2]);
      slot[p] = inversions % 2 == 1 ? std::array<int, 4>{0, 2, 1, 3} : std::array<int, 4>{0, 1, 2, 3};
      // Path barycentrics: 1 - x_a, x_a - x_b, x_b - x_c, x_c.
      const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
      const std::array<Eigen::Vector3d, 4> w{-I.col(perm[0]), I.col(perm[0]) - I.col(perm[1]),
                                             I.col(perm[1]) - I.col(perm[2]), I.col(perm[2])};
      for (size_t m = 0; m < 4; ++m) {
        const size_t column = static_cast<size_t>(slot[p][m]);
        corners[p][column] = path[m];
        local[p].w[column] = w[m];
        local[p].o[column] = m == 0 ? 1.0 : 0.0;
      }
      std::next_permutation(perm.begin(), perm.end());
    }
  }
};

const KuhnTables& kuhn() {
  static const KuhnTables tables;
  return tables;
}

}  // namespace

const std::array<int, 4>& kuhn_corners(int p) { return kuhn().corners[static_cast<size_t>(p)]; }

Eigen::Vector4d kuhn_barycentric(int p, const Eigen::Vector3d& x) {
  const auto& o = kuhn().order[static_cast<size_t>(p)];
  const auto& slot = kuhn().slot[static_cast<size_t>(p)];
  const double path[4] = {1.0 - x(o[0]), x(o[0]) - x(o[1]), x(o[1]) - x(o[2]), x(o[2])};
  Eigen::Vector4d bary;
  for (int m = 0; m < 4; ++m) bary(slot[static_cast<size_t>(m)]) = path[m];
  return bary;
}

TetPlanes kuhn_planes(const Eigen::Vector3i& cell, int p) {
  // In grid coordinates g = cell + x: w·g + (base - w·cell). The offsets are small integers, so
  // exact, and the tet across a face gets exactly the negated plane.
  TetPlanes planes = kuhn().local[static_cast<size_t>(p)];
  const Eigen::Vector3d c = cell.cast<double>();
  for (size_t m = 0; m < 4; ++m) planes.o[m] -= planes.w[m].dot(c);
  return planes;
}

}  // namespace slim
