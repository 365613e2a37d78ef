// The voxel tet domain: the volumetric mesh T that encloses the surface M (paper §II).
//
// voxel_domain(surface, d, options) lays a regular grid of cubes over the surface, aligned with
// the print direction d, keeps every cell that the surface passes through or that lies inside it,
// and splits each kept cell into 6 tets.
//
// Inputs
//   surface  Surface{V #V by 3, F #F by 3}, mesh units (mm). It need not be closed or manifold.
//   d        print direction, any non-zero vector (normalised here).
//   options  VoxelDomainOptions below.
// Output: VoxelDomain
//   mesh.V       #DV by 3 grid nodes used by kept cells, world coordinates (mesh units), in the
//                order of their grid index (k, then j, then i).
//   mesh.T       #DT by 4, 6 tets per kept cell, kept cells in the order of their grid index.
//                Every tet has positive volume (tet_mesh.h).
//   grid         the frame, the cell size and the number of cells (VoxelGrid below).
//   plate_height min over surface vertices of d·v (mm): the build plate.
//   on_plate     #DV, true for the nodes of grid layer 0, which lies exactly on the plate.
//
// The grid frame. e1, e2, d is right-handed and orthonormal, chosen from d alone (print_frame), so
// the same d always gives the same grid. Grid plane 0 along d is the plate: the lowest vertex has
// grid height 0, so the global step can pin the nodes on it and nothing sits below it.
//
// Which cells are kept.
//   * Surface cells: every cell whose closed box, grown by `surface_tolerance` cell units, overlaps
//     a face (exact slab clipping, cells_overlapping_triangle). A face lying on a grid plane thus
//     marks the cells on both sides, and every vertex's cell is kept, so the domain encloses the
//     whole surface, open, non-manifold or not.
//   * Inside cells: signed crossing counts along grid lines through cell centres, in the six
//     directions ±e1, ±e2, ±d. A ray votes "inside" when the faces it crosses do not cancel (the
//     winding number along that ray is non-zero), and a cell needs `min_inside_votes` of the six.
//     Closed meshes give six equal votes; a hole in the mesh only spoils the rays that pass through
//     it, so a shell with a hole in its base is still filled. Signed counts (not parity) keep
//     overlapping shells filled. One pass over the faces per axis: no per-cell winding number,
//     which would be far too slow for a 1M-face mesh. An open bowl is ambiguous: its
//     surface cells are always kept, its air is kept only when enough rays see it as enclosed.
//
// The split. Every cell is split into the 6 Kuhn tets around its main diagonal (node (0,0,0) to
// (1,1,1) of the cell). The split is the same in every cell, so neighbouring cells share their
// face triangles and the tet mesh is conforming.
//
// The memory guard. The grid size is known before anything is allocated; when the worst case
// (every cell kept) exceeds options.max_bytes, voxel_domain throws DomainTooLarge (an
// std::invalid_argument) saying how big the request was and which resolution fits.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/surface.h"
#include "core/tet_mesh.h"

namespace slim {

struct VoxelDomainOptions {
  // Cells along the longest side of the bounding box, measured in the grid frame. 24 gives the
  // sample bunny (1,839 vertices, 3,674 faces) 3,738 cells: 4,899 domain vertices, 22,428 tets.
  int resolution = 24;
  // Budget for the domain and its embedding in bytes, worst case (all cells kept, about 140 bytes
  // per cell): 2 GB, about 14M cells, a resolution of about 240 for a cube. Above: DomainTooLarge.
  double max_bytes = 2e9;
  // Growth of each cell's box, in cell units, in the surface test, so rounding never drops the
  // cell on either side of a face that lies on a grid plane.
  double surface_tolerance = 1e-9;
  // A cell centre is inside when at least this many of the 6 axis rays say so (1..6). 4 is a
  // majority: a closed mesh gives 6, a cell above a hole in the base typically 5.
  int min_inside_votes = 4;
};

// The grid: cell (i, j, k) is the cube [i, i+1] x [j, j+1] x [k, k+1] in grid coordinates (cell
// units), with 0 <= i < cells(0) etc. Grid coordinates of a world point x: (axes x - low) / h.
struct VoxelGrid {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // rows e1, e2, d (world -> frame rotation)
  Eigen::Vector3d low = Eigen::Vector3d::Zero();       // frame coordinates of node (0,0,0), mm
  double cell_size = 1.0;                              // h, mm
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();     // number of cells along e1, e2, d

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

// The Kuhn split of a cell. In local coordinates x = g - (i, j, k) (each in [0, 1]), Kuhn tet p is
// the region 1 >= x_a >= x_b >= x_c >= 0, (a, b, c) = the p-th permutation of (0, 1, 2) in
// lexicographic order. kuhn_corners(p) lists its corners (bit 0: +1 along e1, bit 1: +1 along e2,
// bit 2: +1 along d) in TetMesh::T order, which gives positive volume.
const std::array<int, 4>& kuhn_corners(int p);

// Barycentric coordinates (TetMesh::T order) of local point x in Kuhn tet p. Exact telescoping
// differences of x, so they sum to 1 to rounding.
Eigen::Vector4d kuhn_barycentric(int p, const Eigen::Vector3d& x);

// The planes of Kuhn tet p of cell (i, j, k) in grid coordinates g: w[m]·g + o[m] is the
// barycentric coordinate of corner m (>= 0 inside). The tet sharing a face computes exactly the
// negated value there, which is what makes clipping against neighbouring tets consistent.
struct TetPlanes {
  std::array<Eigen::Vector3d, 4> w;
  std::array<double, 4> o;
};
TetPlanes kuhn_planes(const Eigen::Vector3i& cell, int p);

struct VoxelDomain {
  TetMesh mesh;
  VoxelGrid grid;
  double plate_height = 0.0;
  Eigen::Array<bool, Eigen::Dynamic, 1> on_plate;  // #DV
  // #DT / 6: grid index of each kept cell, ascending; tets 6c .. 6c+5 belong to kept cell c, tet
  // 6c + p being Kuhn tet p.
  std::vector<std::int64_t> kept_cells;
  // grid.cell_count(): the rank of the cell in kept_cells, or -1 when the cell was dropped.
  std::vector<int> cell_rank;
  std::int64_t surface_cells = 0;  // kept because a face passes through them
  std::int64_t inside_cells = 0;   // kept only because they are inside
};

// The grid frame for print direction d (unit): rows e1, e2, d. e1 is the world axis least aligned
// with d (the lowest index on ties) made orthogonal to d; e2 = d x e1. d = +Z gives the identity.
Eigen::Matrix3d print_frame(const Eigen::Vector3d& d);

// What a resolution would cost, computed without allocating anything (one pass over V).
struct VoxelDomainSize {
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();  // along e1, e2, d (saturates at INT_MAX)
  double cell_count = 0;                            // all cells of the grid
  double max_tets = 0;                              // 6 per cell: every cell kept
  double max_bytes = 0;                             // worst-case memory of building the domain
};
VoxelDomainSize estimate_voxel_domain(const Surface& surface, const Eigen::Vector3d& d, int resolution);

// The largest resolution (>= 1) whose worst case fits in max_bytes; 0 when not even 1 fits.
int max_voxel_resolution(const Surface& surface, const Eigen::Vector3d& d, double max_bytes);

// Thrown when the requested grid does not fit the memory budget.
class DomainTooLarge : public std::invalid_argument {
 public:
  DomainTooLarge(const std::string& what, double cells, double tets, double bytes, int fitting_resolution)
      : std::invalid_argument(what), cells(cells), tets(tets), bytes(bytes), fitting_resolution(fitting_resolution) {}
  double cells, tets, bytes;  // what the request would need (worst case)
  int fitting_resolution;     // the largest resolution within the budget
};

// Builds the domain. Throws std::invalid_argument for an empty surface, zero extent, bad
// indices or non-finite coordinates (check_surface), a zero print direction or bad options, and
// DomainTooLarge above the budget.
VoxelDomain voxel_domain(const Surface& surface, const Eigen::Vector3d& d, const VoxelDomainOptions& options = {});

// Cells whose box, grown by `tolerance` cell units, meets the closed triangle (a, b, c), given in
// grid coordinates. Exact up to rounding: the triangle is clipped to each slab of cells along
// e1, then e2, and the clipped polygon's extent along d gives the cells of that column, so the
// work is proportional to the number of cells found. Calls visit(i, j, k) once per cell, i
// outermost, k innermost.
template <class Visit>
void cells_overlapping_triangle(const VoxelGrid& grid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, double tolerance, Visit&& visit);

// ---- implementation of the template above ------------------------------------------------------
namespace detail {
// A convex polygon with at most 16 corners (a triangle cut by 4 planes has at most 7).
struct SlabPolygon {
  std::array<Eigen::Vector3d, 16> p;
  int n = 0;
};
// Keeps the part with sign * (x[axis] - bound) >= 0.
inline void clip_half_space(const SlabPolygon& in, int axis, double bound, double sign, SlabPolygon& out) {
  out.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const Eigen::Vector3d& P = in.p[static_cast<size_t>(i)];
    const Eigen::Vector3d& Q = in.p[static_cast<size_t>((i + 1) % in.n)];
    const double dp = sign * (P(axis) - bound), dq = sign * (Q(axis) - bound);
    if (dp >= 0 && out.n < 16) out.p[static_cast<size_t>(out.n++)] = P;
    if ((dp >= 0) != (dq >= 0) && out.n < 16) {
      Eigen::Vector3d X = P + (dp / (dp - dq)) * (Q - P);
      X(axis) = bound;  // on the plane exactly, whatever the rounding
      out.p[static_cast<size_t>(out.n++)] = X;
    }
  }
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
  if (i0 == i1 && j0 == j1 && k0 == k1) {  // a small triangle inside one cell: the common case
    visit(i0, j0, k0);
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

