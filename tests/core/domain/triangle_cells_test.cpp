// The voxel cells a triangle meets (core/domain/triangle_cells.h) against a brute-force test of every
// cell of the grid: the separating-axis test of a closed box and a closed triangle (the box's
// three axes, the triangle's normal and the nine cross products of their edges). Random
// triangles: large ones across many cells, small ones inside one column of cells but across
// several along d (the rasterizer's short cut for fine meshes), and ones running off the grid.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include "core/domain/triangle_cells.h"

using namespace slim;

namespace {

using Cell = std::tuple<int, int, int>;

// Whether the closed box [lo, hi] and the closed triangle a, b, c meet: no axis separates them.
bool box_meets_triangle(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const std::array<Eigen::Vector3d, 3> p = {a - centre, b - centre, c - centre};
  const std::array<Eigen::Vector3d, 3> edge = {p[1] - p[0], p[2] - p[1], p[0] - p[2]};
  std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                       edge[0].cross(edge[1])};
  for (const Eigen::Vector3d& e : edge)
    for (int k = 0; k < 3; ++k) axes.push_back(e.cross(Eigen::Vector3d::Unit(k)));
  for (const Eigen::Vector3d& axis : axes) {
    if (axis.squaredNorm() == 0.0) continue;
    const double t0 = p[0].dot(axis), t1 = p[1].dot(axis), t2 = p[2].dot(axis);
    const double reach = half.dot(axis.cwiseAbs());
    if (std::min({t0, t1, t2}) > reach || std::max({t0, t1, t2}) < -reach) return false;
  }
  return true;
}

std::vector<Cell> brute_force(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, double tolerance) {
  std::vector<Cell> out;
  for (int i = 0; i < grid.cells(0); ++i)
    for (int j = 0; j < grid.cells(1); ++j)
      for (int k = 0; k < grid.cells(2); ++k) {
        const Eigen::Vector3d lo = Eigen::Vector3d(i, j, k).array() - tolerance;
        if (box_meets_triangle(lo, lo.array() + 1.0 + 2.0 * tolerance, a, b, c)) out.emplace_back(i, j, k);
      }
  return out;
}

std::vector<Cell> rasterized(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c, double tolerance) {
  std::vector<Cell> out;
  cells_overlapping_triangle(grid, a, b, c, tolerance, [&](int i, int j, int k) { out.emplace_back(i, j, k); });
  return out;
}

}  // namespace

TEST(TriangleCells, EveryCellTheTriangleMeetsOnceInOrder) {
  VoxelGrid grid;
  grid.cells = Eigen::Vector3i(7, 6, 9);
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> inside(0.2, 5.8), offset(-0.45, 0.45), across(-1.5, 8.5);
  int tested = 0, one_column_many_layers = 0;
  for (int n = 0; n < 600; ++n) {
    Eigen::Vector3d a, b, c;
    if (n % 3 == 0) {  // large, possibly off the grid
      a << across(gen), across(gen), across(gen);
      b << across(gen), across(gen), across(gen);
      c << across(gen), across(gen), across(gen);
    } else {  // small: inside one column, a cell or two tall
      const Eigen::Vector3d centre(std::floor(inside(gen)) + 0.5, std::floor(inside(gen)) + 0.5, inside(gen) + 1.0);
      auto corner = [&] { return Eigen::Vector3d(centre.x() + offset(gen), centre.y() + offset(gen), centre.z() + 3.0 * offset(gen)); };
      a = corner();
      b = corner();
      c = corner();
    }
    for (double tolerance : {0.0, 0.02}) {
      const std::vector<Cell> found = rasterized(grid, a, b, c, tolerance);
      EXPECT_EQ(found, brute_force(grid, a, b, c, tolerance)) << n << " tolerance " << tolerance;
      ++tested;
      if (!found.empty() && std::get<0>(found.front()) == std::get<0>(found.back()) &&
          std::get<1>(found.front()) == std::get<1>(found.back()) && found.size() > 1)
        ++one_column_many_layers;
    }
  }
  EXPECT_EQ(tested, 1200);
  EXPECT_GT(one_column_many_layers, 200);  // the short cut was taken, and checked
}
