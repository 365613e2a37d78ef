#include "core/print/face_columns.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/uniform_grid.h"
#include "core/platform/parallel_for.h"
#include "core/print/rotation_to_up.h"

namespace slim {

namespace {

// The height at (x, y) of the triangle a, b, c (print frame) when the point lies in its
// projection, edges included; false otherwise or for a triangle seen edge-on.
bool height_over(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double x, double y,
                 double& z) {
  const double det = (b(0) - a(0)) * (c(1) - a(1)) - (c(0) - a(0)) * (b(1) - a(1));
  if (det == 0.0) return false;
  const double u = ((x - a(0)) * (c(1) - a(1)) - (c(0) - a(0)) * (y - a(1))) / det;
  const double v = ((b(0) - a(0)) * (y - a(1)) - (x - a(0)) * (b(1) - a(1))) / det;
  if (u < 0.0 || v < 0.0 || u + v > 1.0) return false;
  z = a(2) + u * (b(2) - a(2)) + v * (c(2) - a(2));
  return true;
}

}  // namespace

Eigen::VectorXd column_heights(const Surface& surface, const Eigen::Vector3d& d, const std::vector<bool>& faces) {
  const Eigen::Index nf = surface.F.rows();
  Eigen::VectorXd heights = Eigen::VectorXd::Zero(nf);
  if (nf == 0 || std::none_of(faces.begin(), faces.end(), [](bool b) { return b; })) return heights;
  const Points P = surface.V * rotation_to_up(d).transpose();  // +Z up
  const Eigen::Vector3d lo = P.colwise().minCoeff(), hi = P.colwise().maxCoeff();
  // About as many columns as faces, square in the plate's plane.
  const Eigen::Vector2d span = (hi - lo).head<2>().cwiseMax(1e-9);
  const double side = std::sqrt(span.prod() / static_cast<double>(nf)) * 2.0;
  const Eigen::Vector3i dims(std::clamp(static_cast<int>(span(0) / side) + 1, 1, 4096),
                             std::clamp(static_cast<int>(span(1) / side) + 1, 1, 4096), 1);
  const Eigen::Vector3d cell(span(0) / dims(0), span(1) / dims(1), std::max(hi(2) - lo(2), 1e-9));
  UniformGrid grid(lo, cell, dims);
  auto corner = [&](Eigen::Index f, int j) -> Eigen::Vector3d { return P.row(surface.F(f, j)).transpose(); };
  grid.fill(static_cast<int>(nf), [&](int f, Eigen::Vector3d& box_lo, Eigen::Vector3d& box_hi) {
    box_lo = corner(f, 0).cwiseMin(corner(f, 1)).cwiseMin(corner(f, 2));
    box_hi = corner(f, 0).cwiseMax(corner(f, 1)).cwiseMax(corner(f, 2));
  });
  const double plate = lo(2);
  parallel_for(static_cast<int>(nf), [&](int f) {
    if (!faces[static_cast<size_t>(f)]) return;
    const Eigen::Vector3d c = (corner(f, 0) + corner(f, 1) + corner(f, 2)) / 3.0;
    double floor = plate;
    for (const int g : grid.items(grid.index(grid.cell_of(c)))) {
      double z = 0.0;
      if (g != f && height_over(corner(g, 0), corner(g, 1), corner(g, 2), c(0), c(1), z) && z < c(2))
        floor = std::max(floor, z);
    }
    heights(f) = std::max(0.0, c(2) - floor);
  });
  return heights;
}

}  // namespace slim
