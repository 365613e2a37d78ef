#include "core/print/overhang_boundary.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace slim {
namespace {

// The closest point to p on the segment [a, b] (a point when a == b).
Eigen::Vector3d closest_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  if (!(length2 > 0.0)) return a;
  return a + std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) * ab;
}

}  // namespace

OverhangBoundary::OverhangBoundary(const Surface& s, const std::vector<bool>& region) {
  if (region.size() != static_cast<size_t>(s.F.rows()))
    throw std::invalid_argument("OverhangBoundary: one region flag per face is needed");
  // The region's faces' edges as (lower vertex, higher vertex): an edge bounds the region when
  // exactly one face of the region runs along it (faces outside it do not count, so only the
  // region's own edges are listed and sorted).
  std::vector<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    if (!region[static_cast<size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
      edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<int, int>> boundary;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary.push_back(edges[i]);
    i = j;
  }
  a_.resize(static_cast<Eigen::Index>(boundary.size()), 3);
  b_.resize(static_cast<Eigen::Index>(boundary.size()), 3);
  for (size_t i = 0; i < boundary.size(); ++i) {
    a_.row(static_cast<Eigen::Index>(i)) = s.V.row(boundary[i].first);
    b_.row(static_cast<Eigen::Index>(i)) = s.V.row(boundary[i].second);
  }
  if (boundary.empty()) return;

  // The grid: about two cubic cells per segment, each segment listed in the cells its bounding box
  // overlaps. Should long segments make that list too long, one cell holds them all (a linear
  // scan: still exact, only slower).
  const int n = static_cast<int>(a_.rows());
  const Eigen::Vector3d lo = a_.colwise().minCoeff().cwiseMin(b_.colwise().minCoeff()).transpose();
  const Eigen::Vector3d hi = a_.colwise().maxCoeff().cwiseMax(b_.colwise().maxCoeff()).transpose();
  const double extent = (hi - lo).maxCoeff();
  const int per_side = std::clamp(static_cast<int>(std::cbrt(2.0 * static_cast<double>(n))), 1, 128);
  const double cell = extent > 0.0 && std::isfinite(extent) ? extent / per_side : 1.0;
  const Eigen::Vector3d cells = Eigen::Vector3d::Constant(cell);
  const UniformGrid sizing(lo, cells, Eigen::Vector3i::Constant(per_side));
  const Eigen::Vector3i dims = sizing.cell_of(hi) + Eigen::Vector3i::Ones();
  auto box_of = [&](int i, Eigen::Vector3d& from, Eigen::Vector3d& to) {
    from = a_.row(i).cwiseMin(b_.row(i)).transpose();
    to = a_.row(i).cwiseMax(b_.row(i)).transpose();
  };
  grid_ = UniformGrid(lo, cells, dims);
  if (grid_.entries(n, box_of) > 32.0 * n + 1e6) grid_ = UniformGrid(lo, cells, Eigen::Vector3i::Ones());
  grid_.fill(n, box_of);
}

double OverhangBoundary::nearest(const Eigen::Vector3d& p, Eigen::Vector3d& closest) const {
  double best = HUGE_VAL;
  if (a_.rows() == 0) return best;
  const int i = grid_.nearest(p, [&](int s) {
    return (closest_on_segment(p, a_.row(s).transpose(), b_.row(s).transpose()) - p).norm();
  }, best);
  if (i < 0) return HUGE_VAL;
  closest = closest_on_segment(p, a_.row(i).transpose(), b_.row(i).transpose());
  return best;
}

Eigen::Vector3d OverhangBoundary::toward_nearest(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const {
  Eigen::Vector3d q;
  const double dist = nearest(p, q);
  if (!std::isfinite(dist)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d h = (q - p) - (q - p).dot(d) * d;
  if (!(h.norm() > 1e-12 * std::max(dist, 1e-300))) return Eigen::Vector3d::Zero();
  return h.normalized();
}

}  // namespace slim
