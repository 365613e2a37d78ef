#include "core/optimizer/coherence.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "core/platform/parallel_for.h"
#include "core/print/overhang_boundary.h"

namespace slim {

namespace {

// Quaternion average (sign-aligned, weighted) of rotations; deterministic.
Eigen::Matrix3d average_rotation(const std::vector<std::pair<double, Eigen::Quaterniond>>& items) {
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  const Eigen::Vector4d ref = items.front().second.coeffs();
  for (const auto& [w, q] : items) {
    const Eigen::Vector4d c = q.coeffs();
    sum += (c.dot(ref) < 0 ? -w : w) * c;
  }
  if (sum.norm() < 1e-300) return Eigen::Matrix3d::Identity();
  Eigen::Quaterniond q;
  q.coeffs() = sum.normalized();
  return q.toRotationMatrix();
}

}  // namespace

TieDirections tie_directions(const Surface& input, const TetMesh& domain, const TetPieces& pieces,
                             const Points& rest_normals, const std::vector<bool>& risky, const Eigen::Vector3d& d,
                             double diag, const CoherenceOptions& coherence) {
  const int nt = static_cast<int>(domain.T.rows());
  const Eigen::Vector3d centre = input.V.colwise().mean().transpose();
  TieDirections out;
  out.tie.resize(static_cast<size_t>(nt));
  out.edge_axis.assign(static_cast<size_t>(nt), Eigen::Vector3d::Zero());
  std::vector<bool> flat_overhang;
  std::unique_ptr<const OverhangBoundary> boundary;
  if (coherence.edge_turns) {
    const double nearly_down = -std::cos(coherence.flat_overhang_deg * M_PI / 180.0);
    flat_overhang.resize(static_cast<size_t>(input.F.rows()));
    for (Eigen::Index f = 0; f < input.F.rows(); ++f)
      flat_overhang[static_cast<size_t>(f)] = risky[static_cast<size_t>(f)] && rest_normals.row(f).dot(d.transpose()) <= nearly_down;
    boundary = std::make_unique<const OverhangBoundary>(input, flat_overhang);
  }
  parallel_for(nt, [&](int t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += domain.V.row(domain.T(t, k)).transpose() / 4.0;
    const Eigen::Vector3d h = (c - centre) - (c - centre).dot(d) * d;
    out.tie[static_cast<size_t>(t)] = h.norm() > 1e-9 * diag ? h.normalized() : Eigen::Vector3d::UnitX();
    if (!boundary) return;
    bool flat = false;
    for (const auto& [face, area] : pieces[static_cast<size_t>(t)]) flat = flat || flat_overhang[static_cast<size_t>(face)];
    if (!flat) return;
    const Eigen::Vector3d toward = boundary->toward_nearest(c, d);
    if (toward.squaredNorm() == 0.0) return;
    out.tie[static_cast<size_t>(t)] = toward;
    out.edge_axis[static_cast<size_t>(t)] = toward.cross(d);  // turns -d towards `toward`
  });
  return out;
}

std::vector<std::vector<int>> tet_neighbours(const Tets& T, Eigen::Index vertex_count, const std::vector<bool>& from) {
  std::vector<int> start(static_cast<size_t>(vertex_count) + 1, 0);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k) ++start[static_cast<size_t>(T(t, k)) + 1];
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<int> around(static_cast<size_t>(start.back())), fill(start.begin(), start.end() - 1);
  for (int t = 0; t < static_cast<int>(T.rows()); ++t)
    for (int k = 0; k < 4; ++k) around[static_cast<size_t>(fill[static_cast<size_t>(T(t, k))]++)] = t;
  std::vector<std::vector<int>> adj(static_cast<size_t>(T.rows()));
  for (int t = 0; t < static_cast<int>(T.rows()); ++t) {
    if (!from[static_cast<size_t>(t)]) continue;
    const int v0 = T(t, 0);
    for (int i = start[static_cast<size_t>(v0)]; i < start[static_cast<size_t>(v0) + 1]; ++i) {
      const int u = around[static_cast<size_t>(i)];
      if (u == t) continue;
      int shared = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) shared += T(t, a) == T(u, b);
      if (shared == 3) adj[static_cast<size_t>(t)].push_back(u);
    }
    // A neighbour across the face opposite v0 does not contain v0: look around v1 for it.
    const int v1 = T(t, 1);
    for (int i = start[static_cast<size_t>(v1)]; i < start[static_cast<size_t>(v1) + 1]; ++i) {
      const int u = around[static_cast<size_t>(i)];
      if (u == t || (T.row(u).array() == v0).any()) continue;
      int shared = 0;
      for (int a = 1; a < 4; ++a)
        for (int b = 0; b < 4; ++b) shared += T(t, a) == T(u, b);
      if (shared == 3) adj[static_cast<size_t>(t)].push_back(u);
    }
  }
  for (int t = 0; t < static_cast<int>(T.rows()); ++t)  // mirror: unmarked tets learn their marked neighbours
    if (from[static_cast<size_t>(t)])
      for (int u : adj[static_cast<size_t>(t)])
        if (!from[static_cast<size_t>(u)]) adj[static_cast<size_t>(u)].push_back(t);
  for (auto& a : adj) std::sort(a.begin(), a.end());
  return adj;
}

void blend_rotations(const std::vector<std::vector<int>>& neighbours, const std::vector<bool>& skip, double smoothing,
                     double propagation, LocalStepState& s) {
  const int nt = static_cast<int>(s.L.size());
  parallel_for(nt, [&](int t) {
    const size_t ts = static_cast<size_t>(t);
    const bool risky = s.risky_area[ts] > 0.0;
    const double share = risky ? smoothing : propagation;
    std::vector<std::pair<double, Eigen::Quaterniond>> items;
    if (!neighbours.empty() && !skip[ts] && share > 0.0)
      for (int u : neighbours[ts])
        if (s.risky_area[static_cast<size_t>(u)] > 0.0 && !skip[static_cast<size_t>(u)])
          items.emplace_back(s.risky_area[static_cast<size_t>(u)], Eigen::Quaterniond(s.extra[static_cast<size_t>(u)]));
    if (items.empty()) {
      if (risky) s.L[ts] = s.extra[ts] * s.L[ts];
      return;
    }
    const Eigen::Quaterniond mean(average_rotation(items));
    const Eigen::Quaterniond own = risky ? Eigen::Quaterniond(s.extra[ts]) : Eigen::Quaterniond::Identity();
    s.L[ts] = own.slerp(share, mean).toRotationMatrix() * s.L[ts];
  });
}

}  // namespace slim
