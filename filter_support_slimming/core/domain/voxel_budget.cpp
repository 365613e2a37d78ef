#include "core/domain/voxel_budget.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>

#include "core/domain/voxel_grid.h"
#include "core/print/print_setup.h"

namespace slim {

namespace {

// Worst-case bytes per grid cell while building the domain and embedding the surface, with every
// cell kept: surface flag 1 + votes 1 + crossing counts 4 + cell rank 4 + kept-cell index 8 +
// 6 tets x 4 ints 96 + the embedding's 6 per-tet offsets 24.
constexpr double kBytesPerCell = 138.0;
// Per grid node: node index 4 + position 24 + plate flag 1.
constexpr double kBytesPerNode = 29.0;
// Tets and nodes are indexed with int.
constexpr double kMaxIndex = static_cast<double>(INT_MAX);

double worst_case_bytes(const Eigen::Vector3d& n) {
  return kBytesPerCell * n.prod() + kBytesPerNode * (n.array() + 1.0).prod();
}

bool fits(const Eigen::Vector3d& n, double max_bytes) {
  return worst_case_bytes(n) <= max_bytes && 6.0 * n.prod() <= kMaxIndex && (n.array() + 1.0).prod() <= kMaxIndex;
}

int max_resolution(const Eigen::Vector3d& extent, double max_bytes) {
  if (!fits(voxel_cells(extent, 1), max_bytes)) return 0;
  int lo = 1, hi = 1 << 30;  // fits(lo), and voxel_cells(hi) is far beyond any index limit
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (fits(voxel_cells(extent, mid), max_bytes) ? lo : hi) = mid;
  }
  return lo;
}

std::string gigabytes(double bytes) {
  std::ostringstream out;
  out.precision(bytes < 1e8 ? 2 : 3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

Eigen::Vector3d extent_of(const Surface& surface, const Eigen::Vector3d& d) {
  check_surface(surface);
  FrameBox box;
  return voxel_extent(surface, print_frame(unit_print_direction(d)), box);
}

}  // namespace

FrameBox frame_box(const Surface& s, const Eigen::Matrix3d& axes) {
  FrameBox box{Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY)};
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) {
    const Eigen::Vector3d p = axes * s.V.row(v).transpose();
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

Eigen::Vector3d voxel_cells(const Eigen::Vector3d& extent, int resolution) {
  const double h = extent.maxCoeff() / resolution;
  Eigen::Vector3d n;
  // The 1e-9 keeps an extent that is an exact multiple of h from growing an empty layer.
  for (int a = 0; a < 3; ++a) n(a) = std::max(1.0, std::ceil(extent(a) / h - 1e-9));
  return n;
}

Eigen::Vector3d voxel_extent(const Surface& s, const Eigen::Matrix3d& axes, FrameBox& box) {
  if (s.F.rows() == 0 || s.V.rows() == 0) throw std::invalid_argument("the mesh has no faces: nothing to enclose");
  box = frame_box(s, axes);
  const Eigen::Vector3d extent = box.hi - box.lo;
  if (!(extent.maxCoeff() > 0.0) || !std::isfinite(extent.maxCoeff()))
    throw std::invalid_argument("the mesh has zero extent (all its vertices coincide): no voxel grid fits it");
  return extent;
}

VoxelDomainSize estimate_voxel_domain(const Surface& surface, const Eigen::Vector3d& d, int resolution) {
  if (resolution < 1) throw std::invalid_argument("the voxel resolution must be at least 1");
  const Eigen::Vector3d n = voxel_cells(extent_of(surface, d), resolution);
  VoxelDomainSize size;
  for (int a = 0; a < 3; ++a) size.cells(a) = static_cast<int>(std::min(n(a), kMaxIndex));
  size.cell_count = n.prod();
  size.max_tets = 6.0 * size.cell_count;
  size.max_bytes = worst_case_bytes(n);
  return size;
}

int max_voxel_resolution(const Surface& surface, const Eigen::Vector3d& d, double max_bytes) {
  return max_resolution(extent_of(surface, d), max_bytes);
}

void require_voxel_budget(const Eigen::Vector3d& extent, int resolution, double max_bytes) {
  const Eigen::Vector3d n = voxel_cells(extent, resolution);
  if (fits(n, max_bytes)) return;
  const int fitting = max_resolution(extent, max_bytes);
  std::ostringstream msg;
  msg << "a voxel resolution of " << resolution << " asks for " << n(0) << " x " << n(1) << " x " << n(2) << " = "
      << n.prod() << " cells (up to " << 6.0 * n.prod() << " tets, about " << gigabytes(worst_case_bytes(n))
      << "), more than the domain budget of " << gigabytes(max_bytes) << " allows";
  if (6.0 * n.prod() > kMaxIndex) msg << " (and more tets than 32-bit indices can number)";
  msg << "; use a resolution of at most " << fitting;
  throw DomainTooLarge(msg.str(), n.prod(), 6.0 * n.prod(), worst_case_bytes(n), fitting);
}

}  // namespace slim
