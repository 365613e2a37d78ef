#include "core/voxel_domain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>

#include "core/overhang.h"

namespace slim {

namespace {

// Worst-case bytes per grid cell while building the domain and embedding the surface, with every
// cell kept: surface flag 1 + votes 1 + crossing counts 4 + cell rank 4 + kept-cell index 8 +
// 6 tets x 4 ints 96 + the embedding's 6 per-tet offsets 24.
constexpr double kBytesPerCell = 138.0;
// Per grid node: node index 4 + position 24 + plate flag 1.
constexpr double kBytesPerNode = 29.0;
// Loops shorter than this run on one thread: on a busy machine a parallel region can cost
// milliseconds, more than the work.
constexpr Eigen::Index kParallelItems = 8192;
// Tets and nodes are indexed with int.
constexpr double kMaxIndex = static_cast<double>(INT_MAX);

struct FrameBox {
  Eigen::Vector3d lo, hi;  // frame coordinates (mm)
};

FrameBox frame_box(const Surface& s, const Eigen::Matrix3d& axes) {
  FrameBox box{Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY)};
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
    const Eigen::Vector3d p = axes * s.V.row(v).transpose();
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

// Cells per axis for a resolution, in double so an absurd request cannot overflow.
Eigen::Vector3d cells_for(const Eigen::Vector3d& extent, int resolution) {
  const double h = extent.maxCoeff() / resolution;
  Eigen::Vector3d n;
  // The 1e-9 keeps an extent that is an exact multiple of h from growing an empty layer.
  for (int a = 0; a < 3; ++a) n(a) = std::max(1.0, std::ceil(extent(a) / h - 1e-9));
  return n;
}

double worst_case_bytes(const Eigen::Vector3d& n) {
  return kBytesPerCell * n.prod() + kBytesPerNode * (n.array() + 1.0).prod();
}

bool fits(const Eigen::Vector3d& n, double max_bytes) {
  return worst_case_bytes(n) <= max_bytes && 6.0 * n.prod() <= kMaxIndex && (n.array() + 1.0).prod() <= kMaxIndex;
}

int max_resolution(const Eigen::Vector3d& extent, double max_bytes) {
  if (!fits(cells_for(extent, 1), max_bytes)) return 0;
  int lo = 1, hi = 1 << 30;  // fits(lo), and cells_for(hi) is far beyond any index limit
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (fits(cells_for(extent, mid), max_bytes) ? lo : hi) = mid;
  }
  return lo;
}

Eigen::Vector3d checked_extent(const Surface& s, const Eigen::Matrix3d& axes, FrameBox& box) {
  check_surface(s);
  if (s.F.rows() == 0 || s.V.rows() == 0) throw std::invalid_argument("the mesh has no faces: nothing to enclose");
  box = frame_box(s, axes);
  const Eigen::Vector3d extent = box.hi - box.lo;
  if (!(extent.maxCoeff() > 0.0) || !std::isfinite(extent.maxCoeff()))
    throw std::invalid_argument("the mesh has zero extent (all its vertices coincide): no voxel grid fits it");
  return extent;
}

std::string gigabytes(double bytes) {
  std::ostringstream out;
  out.precision(bytes < 1e8 ? 2 : 3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

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

Eigen::Matrix3d print_frame(const Eigen::Vector3d& d) {
  int least = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(d(a)) < std::abs(d(least))) least = a;
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(least);
  const Eigen::Vector3d e1 = (axis - axis.dot(d) * d).normalized();
  const Eigen::Vector3d e2 = d.cross(e1);
  Eigen::Matrix3d frame;
  frame.row(0) = e1.transpose();
  frame.row(1) = e2.transpose();
  frame.row(2) = d.transpose();
  return frame;
}

VoxelDomainSize estimate_voxel_domain(const Surface& surface, const Eigen::Vector3d& d, int resolution) {
  if (resolution < 1) throw std::invalid_argument("the voxel resolution must be at least 1");
  FrameBox box;
  const Eigen::Vector3d n = cells_for(checked_extent(surface, print_frame(unit_print_direction(d)), box), resolution);
  VoxelDomainSize size;
  for (int a = 0; a < 3; ++a) size.cells(a) = static_cast<int>(std::min(n(a), kMaxIndex));
  size.cell_count = n.prod();
  size.max_tets = 6.0 * size.cell_count;
  size.max_bytes = worst_case_bytes(n);
  return size;
}

int max_voxel_resolution(const Surface& surface, const Eigen::Vector3d& d, double max_bytes) {
  FrameBox box;
  return max_resolution(checked_extent(surface, print_frame(unit_print_direction(d)), box), max_bytes);
}

VoxelDomain voxel_domain(const Surface& surface, const Eigen::Vector3d& print_direction,
                         const VoxelDomainOptions& options) {
  if (options.resolution < 1) throw std::invalid_argument("the voxel resolution must be at least 1");
  if (!(options.max_bytes > 0.0)) throw std::invalid_argument("the domain memory budget must be positive");
  if (!(options.surface_tolerance >= 0.0 && options.surface_tolerance < 0.5))
    throw std::invalid_argument("the voxel surface tolerance must lie in [0, 0.5) cell");
  if (options.min_inside_votes < 1 || options.min_inside_votes > 7)
    throw std::invalid_argument("min_inside_votes must lie in 1..6 (7 keeps only the surface cells)");
  const Eigen::Vector3d d = unit_print_direction(print_direction);

  VoxelDomain dom;
  VoxelGrid& grid = dom.grid;
  grid.axes = print_frame(d);
  FrameBox box;
  const Eigen::Vector3d extent = checked_extent(surface, grid.axes, box);

  // The memory guard, before anything proportional to the grid is allocated.
  const Eigen::Vector3d n = cells_for(extent, options.resolution);
  if (!fits(n, options.max_bytes)) {
    const int fitting = max_resolution(extent, options.max_bytes);
    std::ostringstream msg;
    msg << "a voxel resolution of " << options.resolution << " asks for " << n(0) << " x " << n(1) << " x " << n(2)
        << " = " << n.prod() << " cells (up to " << 6.0 * n.prod() << " tets, about " << gigabytes(worst_case_bytes(n))
        << "), more than the domain budget of " << gigabytes(options.max_bytes) << " allows";
    if (6.0 * n.prod() > kMaxIndex) msg << " (and more tets than 32-bit indices can number)";
    msg << "; use a resolution of at most " << fitting;
    throw DomainTooLarge(msg.str(), n.prod(), 6.0 * n.prod(), worst_case_bytes(n), fitting);
  }
  grid.cells = n.cast<int>();
  grid.low = box.lo;
  grid.cell_size = extent.maxCoeff() / options.resolution;
  dom.plate_height = box.lo(2);

  // Vertices in grid coordinates; the lowest vertex has height exactly 0.
  const Points Q = ((surface.V * grid.axes.transpose()).rowwise() - grid.low.transpose()) / grid.cell_size;
  const size_t ncells = static_cast<size_t>(grid.cell_count());

  // Surface cells: every vertex's cell (unreferenced vertices too), then every face's cells.
  std::vector<std::uint8_t> surface_cell(ncells, 0);
  for (Eigen::Index v = 0; v < Q.rows(); ++v) {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) c(a) = std::clamp(static_cast<int>(std::floor(Q(v, a))), 0, grid.cells(a) - 1);
    surface_cell[static_cast<size_t>(grid.cell_index(c(0), c(1), c(2)))] = 1;
  }
  const Triangles& F = surface.F;
#pragma omp parallel for schedule(dynamic, 1024) if (F.rows() > kParallelItems)
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    cells_overlapping_triangle(grid, Q.row(F(f, 0)).transpose(), Q.row(F(f, 1)).transpose(), Q.row(F(f, 2)).transpose(),
                               options.surface_tolerance, [&](int i, int j, int k) {
                                 const size_t c = static_cast<size_t>(grid.cell_index(i, j, k));
#pragma omp atomic write
                                 surface_cell[c] = 1;
                               });

  // Inside cells: six ray votes per cell centre.
  std::vector<std::uint8_t> votes(ncells, 0);
  if (options.min_inside_votes <= 6) {
    std::vector<int> delta(ncells);
    for (int axis = 0; axis < 3; ++axis) vote_along_axis(Q, F, grid, axis, surface_cell, votes, delta);
  }

  // Kept cells, in grid-index order.
  dom.cell_rank.assign(ncells, -1);
  for (size_t c = 0; c < ncells; ++c) {
    const bool inside = votes[c] >= options.min_inside_votes;
    if (!surface_cell[c] && !inside) continue;
    dom.cell_rank[c] = static_cast<int>(dom.kept_cells.size());
    dom.kept_cells.push_back(static_cast<std::int64_t>(c));
    (surface_cell[c] ? dom.surface_cells : dom.inside_cells) += 1;
  }

  // Nodes of kept cells, compactly numbered in node-index order.
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

  // Six Kuhn tets per kept cell.
  dom.mesh.T.resize(static_cast<Eigen::Index>(6 * dom.kept_cells.size()), 4);
  for (size_t r = 0; r < dom.kept_cells.size(); ++r)
    for (int p = 0; p < 6; ++p)
      for (int m = 0; m < 4; ++m)
        dom.mesh.T(static_cast<Eigen::Index>(6 * r) + p, m) =
            node_index[static_cast<size_t>(node_of(dom.kept_cells[r], kuhn_corners(p)[static_cast<size_t>(m)]))];
  return dom;
}

}  // namespace slim
