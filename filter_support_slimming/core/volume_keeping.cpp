#include "core/volume_keeping.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/parallel_for.h"

namespace slim {
namespace {

void require_in_range(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("volume keeping: " + what);
}

// The coefficients of det[a + l p, b + l q, c + l r] in 1, l, l², l³.
Eigen::Vector4d cubic_terms(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c,
                            const Eigen::RowVector3d& p, const Eigen::RowVector3d& q, const Eigen::RowVector3d& r) {
  return {a.dot(b.cross(c)), p.dot(b.cross(c)) + a.dot(q.cross(c)) + a.dot(b.cross(r)),
          a.dot(q.cross(r)) + p.dot(b.cross(r)) + p.dot(q.cross(c)), p.dot(q.cross(r))};
}

// The faces' minors summed per node triple. Faces are grouped by the tets their corners lie in
// (one tet for most faces; a face across tets has up to 12 nodes): a group's nodes in increasing
// order and, for each three of them, the summed minor.
class NodeTriples {
 public:
  void add(const Embedding& e, int a, int b, int c) {
    const Group& g = group_of(e, {a, b, c});
    Eigen::Matrix<double, 3, 12> w = Eigen::Matrix<double, 3, 12>::Zero();
    const std::array<int, 3> corners{a, b, c};
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 4; ++k) {
        const int node = e.vertex_nodes(corners[static_cast<size_t>(r)], k);
        const auto at = std::lower_bound(g.nodes.begin(), g.nodes.begin() + g.count, node) - g.nodes.begin();
        w(r, at) += e.vertex_bary(corners[static_cast<size_t>(r)], k);
      }
    size_t slot = g.first;
    for (int i = 0; i < g.count; ++i)
      for (int j = i + 1; j < g.count; ++j)
        for (int k = j + 1; k < g.count; ++k, ++slot) {
          Eigen::Matrix3d minor;
          minor << w.col(i), w.col(j), w.col(k);
          triples_[slot].coefficient += minor.determinant();
        }
  }

  std::vector<VolumeKeeping::Triple> take() { return std::move(triples_); }

 private:
  struct Group {
    std::array<int, 12> nodes;
    int count = 0;
    size_t first = 0;  // its first triple in triples_
  };
  struct KeyHash {
    size_t operator()(const std::array<int, 3>& k) const {
      const auto u = [](int x) { return static_cast<unsigned long long>(static_cast<unsigned>(x)); };
      return std::hash<unsigned long long>()((u(k[0]) * 1000003ULL + u(k[1])) * 1000003ULL + u(k[2]));
    }
  };

  // The group of the tets of `corners`, made the first time: a face in one tet finds it by the
  // tet, one across tets by the sorted tets.
  const Group& group_of(const Embedding& e, const std::array<int, 3>& corners) {
    std::array<int, 3> tets{e.vertex_tet(corners[0]), e.vertex_tet(corners[1]), e.vertex_tet(corners[2])};
    const bool one_tet = tets[0] == tets[1] && tets[1] == tets[2];
    if (one_tet && static_cast<size_t>(tets[0]) >= by_tet_.size()) by_tet_.resize(static_cast<size_t>(tets[0]) + 1, -1);
    std::sort(tets.begin(), tets.end());
    if (one_tet && by_tet_[static_cast<size_t>(tets[0])] >= 0) return groups_[static_cast<size_t>(by_tet_[static_cast<size_t>(tets[0])])];
    if (!one_tet) {
      const auto found = index_.find(tets);
      if (found != index_.end()) return groups_[found->second];
    }
    Group g;
    for (int corner : corners)
      for (int k = 0; k < 4; ++k) g.nodes[static_cast<size_t>(g.count++)] = e.vertex_nodes(corner, k);
    std::sort(g.nodes.begin(), g.nodes.begin() + g.count);
    g.count = static_cast<int>(std::unique(g.nodes.begin(), g.nodes.begin() + g.count) - g.nodes.begin());
    g.first = triples_.size();
    for (int i = 0; i < g.count; ++i)
      for (int j = i + 1; j < g.count; ++j)
        for (int k = j + 1; k < g.count; ++k) triples_.push_back({{g.nodes[i], g.nodes[j], g.nodes[k]}, 0.0});
    if (one_tet) by_tet_[static_cast<size_t>(tets[0])] = static_cast<int>(groups_.size());
    else index_.emplace(tets, groups_.size());
    groups_.push_back(g);
    return groups_.back();
  }

  std::vector<int> by_tet_;  // the group of the faces in one tet, by tet (-1: none yet)
  std::unordered_map<std::array<int, 3>, size_t, KeyHash> index_;
  std::vector<Group> groups_;
  std::vector<VolumeKeeping::Triple> triples_;
};

// Every triple of `triples` once (groups share them: the nodes of a tet's face are in the groups
// of both tets and of the faces across them), its coefficients summed in the order given; in
// increasing order of nodes; none with a coefficient of zero.
std::vector<VolumeKeeping::Triple> merged(std::vector<VolumeKeeping::Triple> triples) {
  std::stable_sort(triples.begin(), triples.end(),
                   [](const VolumeKeeping::Triple& x, const VolumeKeeping::Triple& y) { return x.nodes < y.nodes; });
  std::vector<VolumeKeeping::Triple> out;
  for (const VolumeKeeping::Triple& t : triples) {
    if (!out.empty() && out.back().nodes == t.nodes) out.back().coefficient += t.coefficient;
    else out.push_back(t);
  }
  out.erase(std::remove_if(out.begin(), out.end(), [](const VolumeKeeping::Triple& t) { return t.coefficient == 0.0; }),
            out.end());
  return out;
}

}  // namespace

VolumeKeeping::VolumeKeeping(const Embedding& e, const Triangles& F, Eigen::Index domain_vertices)
    : domain_vertices_(domain_vertices) {
  const Eigen::Index surface = e.vertex_nodes.rows();
  require_in_range(e.vertex_bary.rows() == surface && e.vertex_tet.rows() == surface,
                   "the embedding's weights, nodes and tets differ in count");
  require_in_range(F.size() == 0 || (F.minCoeff() >= 0 && F.maxCoeff() < surface),
                   "a face names a vertex the embedding does not hold");
  require_in_range(e.vertex_nodes.size() == 0 || (e.vertex_nodes.minCoeff() >= 0 && e.vertex_nodes.maxCoeff() < domain_vertices),
                   "the embedding names a domain vertex out of range");
  // The centroid's weight on each domain vertex.
  centroid_weights_ = Eigen::VectorXd::Zero(domain_vertices);
  for (Eigen::Index i = 0; i < surface; ++i)
    for (int k = 0; k < 4; ++k) centroid_weights_(e.vertex_nodes(i, k)) += e.vertex_bary(i, k) / static_cast<double>(surface);
  // Each face's det[x_a, x_b, x_c], with x = W V (a corner's weights on its tet's nodes), is
  // multilinear in V: the sum over every three nodes i < j < k of the face's of the minor of W
  // at columns i, j, k times det[V_i, V_j, V_k] (a repeated node gives zero). Faces whose corners
  // lie in the same tets share their nodes, so their minors are summed once: within blocks of
  // faces of a fixed size on the threads, then block after block (the same bits on any number of
  // threads).
  constexpr Eigen::Index kBlock = 1 << 16;
  std::vector<std::vector<Triple>> blocks(static_cast<size_t>((F.rows() + kBlock - 1) / kBlock));
  parallel_for(static_cast<int>(blocks.size()), [&](int b) {
    NodeTriples triples;
    for (Eigen::Index f = b * kBlock; f < std::min(F.rows(), (b + 1) * kBlock); ++f) triples.add(e, F(f, 0), F(f, 1), F(f, 2));
    blocks[static_cast<size_t>(b)] = triples.take();
  });
  std::vector<Triple> all;
  for (const std::vector<Triple>& block : blocks) all.insert(all.end(), block.begin(), block.end());
  triples_ = merged(std::move(all));
}

void VolumeKeeping::centred(const Points& V, RowPoints& out) const {
  const Eigen::RowVector3d centre = centroid_weights_.transpose() * V;
  out = V.rowwise() - centre;
}

Points VolumeKeeping::load(const Points& V_start) {
  // Vol = 1/6 sum of c_ijk det[V_i, V_j, V_k] about the centroid; d/dV_i = c_ijk (V_j x V_k) / 6.
  centred(V_start, P_);
  Points out = Points::Zero(domain_vertices_, 3);
  for (const Triple& t : triples_) {
    const Eigen::RowVector3d a = P_.row(t.nodes[0]), b = P_.row(t.nodes[1]), c = P_.row(t.nodes[2]);
    out.row(t.nodes[0]) += t.coefficient / 6.0 * b.cross(c);
    out.row(t.nodes[1]) += t.coefficient / 6.0 * c.cross(a);
    out.row(t.nodes[2]) += t.coefficient / 6.0 * a.cross(b);
  }
  return out;
}

double VolumeKeeping::keep(double target, const Points& u, Points& proposed) {
  // The domain moves linearly with lambda, and so does the surface's centroid, so
  // Vol(lambda) = (d0 + d1 lambda + d2 lambda^2 + d3 lambda^3) / 6 exactly: one pass over the
  // node triples for the coefficients, then Newton's method on the cubic alone.
  centred(proposed, P_);
  centred(u, Q_);
  Eigen::Vector4d d = Eigen::Vector4d::Zero();
  for (const Triple& t : triples_)
    d += t.coefficient * cubic_terms(P_.row(t.nodes[0]), P_.row(t.nodes[1]), P_.row(t.nodes[2]), Q_.row(t.nodes[0]),
                                     Q_.row(t.nodes[1]), Q_.row(t.nodes[2]));
  d /= 6.0;
  auto volume = [&](double l) { return d(0) + l * (d(1) + l * (d(2) + l * d(3))); };
  auto slope = [&](double l) { return d(1) + l * (2.0 * d(2) + l * 3.0 * d(3)); };
  double lambda = 0.0;
  for (int step = 0; step < 20 && std::abs(volume(lambda) - target) > 1e-12 * std::abs(target); ++step) {
    const double s = slope(lambda);
    if (!(std::abs(s) > 0.0) || !std::isfinite(s)) break;
    const double next = lambda + (target - volume(lambda)) / s;
    if (!std::isfinite(next)) break;
    lambda = next;
  }
  if (lambda != 0.0) proposed += lambda * u;
  return lambda;
}

Points volume_load(const Embedding& e, const Triangles& F, const Points& V_start) {
  return VolumeKeeping(e, F, V_start.rows()).load(V_start);
}

double keep_volume(const Embedding& e, const Triangles& F, double target, const Points& u, Points& proposed) {
  return VolumeKeeping(e, F, proposed.rows()).keep(target, u, proposed);
}

}  // namespace slim
