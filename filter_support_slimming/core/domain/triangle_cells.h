// The voxel cells a triangle meets: the rasterizer behind the voxel domain's surface cells
// (voxel_domain.h) and the embedding's candidate tets (tet_locator.h).
//
//   cells_overlapping_triangle(grid, a, b, c, tolerance, visit)
//
// Inputs: the grid (voxel_grid.h); the triangle's corners a, b, c in grid coordinates (cell
//         units); tolerance >= 0, how far each cell's box is grown, in cell units.
// Output: visit(i, j, k) once for every cell whose grown closed box meets the closed triangle,
//         i outermost, k innermost.
// Exact up to rounding: the triangle is clipped to each slab of cells along e1, then e2
// (convex_polygon.h; cut corners are put on the slab planes exactly), and the clipped polygon's
// extent along d gives the cells of that column, so the work is proportional to the number of
// cells found.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "core/domain/voxel_grid.h"
#include "core/geometry/convex_polygon.h"

namespace slim {

namespace detail {
// A triangle cut by 4 planes has at most 7 corners.
using SlabPolygon = ConvexPolygon<16>;

// Keeps the part with sign * (x[axis] - bound) >= 0.
inline void clip_half_space(const SlabPolygon& in, int axis, double bound, double sign, SlabPolygon& out) {
  std::array<double, 16> dist;
  std::array<bool, 16> inside;
  for (int i = 0; i < in.n; ++i) {
    dist[static_cast<size_t>(i)] = sign * (in.p[static_cast<size_t>(i)](axis) - bound);
    inside[static_cast<size_t>(i)] = dist[static_cast<size_t>(i)] >= 0;
  }
  clip_convex_polygon(in, dist.data(), inside.data(), out, [&](Eigen::Vector3d& X) { X(axis) = bound; });
}
inline void clip_slab(const SlabPolygon& in, int axis, double lo, double hi, SlabPolygon& out) {
  SlabPolygon tmp;
  clip_half_space(in, axis, lo, 1.0, tmp);
  clip_half_space(tmp, axis, hi, -1.0, out);
}
inline void polygon_range(const SlabPolygon& poly, int axis, double& lo, double& hi) {
  lo = hi = poly.p[0](axis);
  for (int i = 1; i < poly.n; ++i) {
    lo = std::min(lo, poly.p[static_cast<size_t>(i)](axis));
    hi = std::max(hi, poly.p[static_cast<size_t>(i)](axis));
  }
}
// Cells c in [0, n) whose span [c - tol, c + 1 + tol] meets [lo, hi].
inline void cell_range(double lo, double hi, double tol, int n, int& first, int& last) {
  first = static_cast<int>(std::max(0.0, std::ceil(lo - tol - 1.0)));
  last = static_cast<int>(std::min(static_cast<double>(n - 1), std::floor(hi + tol)));
}
}  // namespace detail

template <class Visit>
void cells_overlapping_triangle(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, double tolerance, Visit&& visit) {
  int i0, i1, j0, j1, k0, k1;
  const Eigen::Vector3d lower = a.cwiseMin(b).cwiseMin(c), upper = a.cwiseMax(b).cwiseMax(c);
  detail::cell_range(lower(0), upper(0), tolerance, grid.cells(0), i0, i1);
  detail::cell_range(lower(1), upper(1), tolerance, grid.cells(1), j0, j1);
  detail::cell_range(lower(2), upper(2), tolerance, grid.cells(2), k0, k1);
  if (i0 == i1 && j0 == j1 && k0 == k1) {  // a small triangle inside one cell
    visit(i0, j0, k0);
    return;
  }
  if (i0 == i1 && j0 == j1 && lower(0) - (i0 - tolerance) >= 0 && (i0 + 1 + tolerance) - upper(0) >= 0 &&
      lower(1) - (j0 - tolerance) >= 0 && (j0 + 1 + tolerance) - upper(1) >= 0) {
    // A small triangle inside one column (the common case on a fine mesh): the slabs' clips
    // would keep it whole, so its cells are those of its own extent along d.
    for (int k = k0; k <= k1; ++k) visit(i0, j0, k);
    return;
  }
  detail::SlabPolygon tri, row, column;
  tri.p[0] = a;
  tri.p[1] = b;
  tri.p[2] = c;
  tri.n = 3;
  double lo, hi;
  for (int i = i0; i <= i1; ++i) {
    detail::clip_slab(tri, 0, i - tolerance, i + 1 + tolerance, row);
    if (row.n == 0) continue;
    detail::polygon_range(row, 1, lo, hi);
    detail::cell_range(lo, hi, tolerance, grid.cells(1), j0, j1);
    for (int j = j0; j <= j1; ++j) {
      detail::clip_slab(row, 1, j - tolerance, j + 1 + tolerance, column);
      if (column.n == 0) continue;
      detail::polygon_range(column, 2, lo, hi);
      detail::cell_range(lo, hi, tolerance, grid.cells(2), k0, k1);
      for (int k = k0; k <= k1; ++k) visit(i, j, k);
    }
  }
}

}  // namespace slim
