#include "core/domain/voxel_domain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <climits>
#include <cmath>

#include "core/print/print_setup.h"

namespace slim {

namespace {

// Loops shorter than this run on one thread: on a busy machine a parallel region can cost
// milliseconds, more than the work.
constexpr Eigen::Index kParallelItems = 8192;

// 2D cross product (u, v components) of b - a and c - a.
double cross2(double au, double av, double bu, double bv, double cu, double cv) {
  return (bu - au) * (cv - av) - (bv - av) * (cu - au);
}

// Edge function of the directed edge P -> Q at X, with X pushed by (eps, eps^2) when it lies on
// the edge (simulation of simplicity). The value is computed from the lexicographically smaller
// end, so the two triangles sharing an edge see exactly opposite values and a ray through the edge
// is counted once. Returns -1, 0 (degenerate edge) or +1.
int edge_sign(double pu, double pv, double qu, double qv, double xu, double xv) {
  const bool forward = pu < qu || (pu == qu && pv <= qv);
  const double e = forward ? cross2(pu, pv, qu, qv, xu, xv) : -cross2(qu, qv, pu, pv, xu, xv);
  if (e != 0.0) return e > 0 ? 1 : -1;
  const double du = qu - pu, dv = qv - pv;
  if (dv != 0.0) return dv < 0 ? 1 : -1;
  return du > 0 ? 1 : (du < 0 ? -1 : 0);
}

// Adds the faces' signed crossings of every grid line along `axis` to `votes`: a cell centre gets
// one vote when the crossings below it do not cancel and one when those above it do not.
void vote_along_axis(const Points& Q, const Triangles& F, const VoxelGrid& grid, int axis,
                     const std::vector<std::uint8_t>& surface, std::vector<std::uint8_t>& votes,
                     std::vector<int>& delta) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) is right-handed
  const int nu = grid.cells(u), nv = grid.cells(v), na = grid.cells(axis);
  auto cell_of = [&](int iu, int iv, int ia) {
    Eigen::Vector3i c;
    c(u) = iu;
    c(v) = iv;
    c(axis) = ia;
    return grid.cell_index(c(0), c(1), c(2));
  };
  std::fill(delta.begin(), delta.end(), 0);
  std::vector<int> total(static_cast<size_t>(nu) * static_cast<size_t>(nv), 0);

#pragma omp parallel for schedule(dynamic, 4096) if (F.rows() > kParallelItems)
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = Q.row(F(f, 0)).transpose(), p1 = Q.row(F(f, 1)).transpose(),
                          p2 = Q.row(F(f, 2)).transpose();
    // The 2D cross product is the axis component of the normal, since (u, v, axis) is cyclic.
    const double area2 = cross2(p0(u), p0(v), p1(u), p1(v), p2(u), p2(v));
    if (area2 == 0.0) continue;  // parallel to the lines: no crossing
    const int orientation = area2 > 0 ? 1 : -1;
    const int crossing = -orientation;  // entering (normal against the axis) counts +1
    const double umin = std::min({p0(u), p1(u), p2(u)}), umax = std::max({p0(u), p1(u), p2(u)});
    const double vmin = std::min({p0(v), p1(v), p2(v)}), vmax = std::max({p0(v), p1(v), p2(v)});
    const int iu0 = std::max(0, static_cast<int>(std::ceil(umin - 0.5)));
    const int iu1 = std::min(nu - 1, static_cast<int>(std::floor(umax - 0.5)));
    const int iv0 = std::max(0, static_cast<int>(std::ceil(vmin - 0.5)));
    const int iv1 = std::min(nv - 1, static_cast<int>(std::floor(vmax - 0.5)));
    for (int iu = iu0; iu <= iu1; ++iu)
      for (int iv = iv0; iv <= iv1; ++iv) {
        const double xu = iu + 0.5, xv = iv + 0.5;
        if (edge_sign(p1(u), p1(v), p2(u), p2(v), xu, xv) != orientation ||
            edge_sign(p2(u), p2(v), p0(u), p0(v), xu, xv) != orientation ||
            edge_sign(p0(u), p0(v), p1(u), p1(v), xu, xv) != orientation)
          continue;
        // Where the line meets the face: barycentric interpolation of the axis coordinate.
        const double w0 = cross2(xu, xv, p1(u), p1(v), p2(u), p2(v));
        const double w1 = cross2(xu, xv, p2(u), p2(v), p0(u), p0(v));
        const double w2 = area2 - w0 - w1;
        const double t = (w0 * p0(axis) + w1 * p1(axis) + w2 * p2(axis)) / area2;
        const size_t line = static_cast<size_t>(iu) * static_cast<size_t>(nv) + static_cast<size_t>(iv);
#pragma omp atomic
        total[line] += crossing;
        // The first cell whose centre lies above the crossing.
        const double first = std::floor(t - 0.5) + 1.0;
        if (first >= na) continue;
        const std::int64_t cell = cell_of(iu, iv, static_cast<int>(std::max(0.0, first)));
#pragma omp atomic
        delta[static_cast<size_t>(cell)] += crossing;
      }
  }

#pragma omp parallel for schedule(static) if (grid.cell_count() > 4 * kParallelItems)
  for (int iu = 0; iu < nu; ++iu)
    for (int iv = 0; iv < nv; ++iv) {
      const int line_total = total[static_cast<size_t>(iu) * static_cast<size_t>(nv) + static_cast<size_t>(iv)];
      int below = 0;
      for (int ia = 0; ia < na; ++ia) {
        const size_t cell = static_cast<size_t>(cell_of(iu, iv, ia));
        below += delta[cell];
        if (surface[cell]) continue;
        votes[cell] = static_cast<std::uint8_t>(votes[cell] + (below != 0) + (line_total - below != 0));
      }
    }
}

void check_options(const VoxelDomainOptions& options) {
  if (options.resolution < 1) throw std::invalid_argument("the voxel resolution must be at least 1");
  if (!(options.max_bytes > 0.0)) throw std::invalid_argument("the domain memory budget must be positive");
  if (!(options.surface_tolerance >= 0.0 && options.surface_tolerance < 0.5))
    throw std::invalid_argument("the voxel surface tolerance must lie in [0, 0.5) cell");
  if (options.min_inside_votes < 1 || options.min_inside_votes > 7)
    throw std::invalid_argument("min_inside_votes must lie in 1..6 (7 keeps only the surface cells)");
}

// Every vertex's cell (unreferenced vertices too), then every face's cells. Q: the vertices in grid
// coordinates.
std::vector<std::uint8_t> surface_cells(const Points& Q, const Triangles& F, const VoxelGrid& grid, double tolerance) {
  std::vector<std::uint8_t> surface_cell(static_cast<size_t>(grid.cell_count()), 0);
  for (Eigen::Index v = 0; v < Q.rows(); ++v) {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) c(a) = std::clamp(static_cast<int>(std::floor(Q(v, a))), 0, grid.cells(a) - 1);
    surface_cell[static_cast<size_t>(grid.cell_index(c(0), c(1), c(2)))] = 1;
  }
#pragma omp parallel for schedule(dynamic, 1024) if (F.rows() > kParallelItems)
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    cells_overlapping_triangle(grid, Q.row(F(f, 0)).transpose(), Q.row(F(f, 1)).transpose(), Q.row(F(f, 2)).transpose(),
                               tolerance, [&](int i, int j, int k) {
                                 const size_t c = static_cast<size_t>(grid.cell_index(i, j, k));
#pragma omp atomic write
                                 surface_cell[c] = 1;
                               });
  return surface_cell;
}

// The kept cells in grid-index order: the surface cells and those with enough inside votes.
void keep_cells(const std::vector<std::uint8_t>& surface_cell, const std::vector<std::uint8_t>& votes,
                int min_inside_votes, VoxelDomain& dom) {
  dom.cell_rank.assign(surface_cell.size(), -1);
  for (size_t c = 0; c < surface_cell.size(); ++c) {
    const bool inside = votes[c] >= min_inside_votes;
    if (!surface_cell[c] && !inside) continue;
    dom.cell_rank[c] = static_cast<int>(dom.kept_cells.size());
    dom.kept_cells.push_back(static_cast<std::int64_t>(c));
    (surface_cell[c] ? dom.surface_cells : dom.inside_cells) += 1;
  }
}

// The nodes of the kept cells, compactly numbered in node-index order, and six Kuhn tets per cell.
void build_tets(VoxelDomain& dom) {
  const VoxelGrid& grid = dom.grid;
  const std::int64_t nx = grid.cells(0), ny = grid.cells(1);
  const std::int64_t sx = nx + 1, sy = ny + 1;
  auto node_of = [&](std::int64_t cell, int corner) {
    const std::int64_t i = cell % nx, j = (cell / nx) % ny, k = cell / (nx * ny);
    return (i + (corner & 1)) + sx * ((j + ((corner >> 1) & 1)) + sy * (k + ((corner >> 2) & 1)));
  };
  std::vector<int> node_index(static_cast<size_t>(sx * sy * (grid.cells(2) + 1)), -1);
  for (std::int64_t c : dom.kept_cells)
    for (int corner = 0; corner < 8; ++corner) node_index[static_cast<size_t>(node_of(c, corner))] = 0;
  int nodes = 0;
  for (int& id : node_index)
    if (id == 0) id = nodes++;
  dom.mesh.V.resize(nodes, 3);
  dom.on_plate.resize(nodes);
  for (size_t g = 0; g < node_index.size(); ++g) {
    const int id = node_index[g];
    if (id < 0) continue;
    const std::int64_t gi = static_cast<std::int64_t>(g);
    const Eigen::Vector3d node(static_cast<double>(gi % sx), static_cast<double>((gi / sx) % sy),
                               static_cast<double>(gi / (sx * sy)));
    dom.mesh.V.row(id) = grid.to_world(node).transpose();
    dom.on_plate(id) = node(2) == 0.0;
  }
  dom.mesh.T.resize(static_cast<Eigen::Index>(6 * dom.kept_cells.size()), 4);
  for (size_t r = 0; r < dom.kept_cells.size(); ++r)
    for (int p = 0; p < 6; ++p)
      for (int m = 0; m < 4; ++m)
        dom.mesh.T(static_cast<Eigen::Index>(6 * r) + p, m) =
            node_index[static_cast<size_t>(node_of(dom.kept_cells[r], kuhn_corners(p)[static_cast<size_t>(m)]))];
}

}  // namespace

VoxelDomain voxel_domain(const Surface& surface, const Eigen::Vector3d& print_direction,
                         const VoxelDomainOptions& options) {
  return voxel_domain(CheckedSurface(surface), print_direction, options);
}

VoxelDomain voxel_domain(const CheckedSurface& checked, const Eigen::Vector3d& print_direction,
                         const VoxelDomainOptions& options) {
  check_options(options);
  const Surface& surface = checked.get();
  const Eigen::Vector3d d = unit_print_direction(print_direction);

  VoxelDomain dom;
  VoxelGrid& grid = dom.grid;
  grid.axes = print_frame(d);
  FrameBox box;
  const Eigen::Vector3d extent = voxel_extent(surface, grid.axes, box);
  // The memory guard, before anything proportional to the grid is allocated.
  require_voxel_budget(extent, options.resolution, options.max_bytes);
  grid.cells = voxel_cells(extent, options.resolution).cast<int>();
  grid.low = box.lo;
  grid.cell_size = extent.maxCoeff() / options.resolution;
  dom.plate_height = box.lo(2);

  // Vertices in grid coordinates; the lowest vertex has height exactly 0.
  const Points Q = ((surface.V * grid.axes.transpose()).rowwise() - grid.low.transpose()) / grid.cell_size;
  const std::vector<std::uint8_t> surface_cell = surface_cells(Q, surface.F, grid, options.surface_tolerance);
  // Inside cells: six ray votes per cell centre.
  std::vector<std::uint8_t> votes(surface_cell.size(), 0);
  if (options.min_inside_votes <= 6) {
    std::vector<int> delta(surface_cell.size());
    for (int axis = 0; axis < 3; ++axis) vote_along_axis(Q, surface.F, grid, axis, surface_cell, votes, delta);
  }
  keep_cells(surface_cell, votes, options.min_inside_votes, dom);
  build_tets(dom);
  return dom;
}

}  // namespace slim
