#include "core/optimizer/volume_keeping.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

#include "core/platform/parallel_for.h"

namespace slim {
namespace {

// Owner of each item (items 0..n-1 in order) listed per owner, items in increasing order: a
// counting sort.
template <class OwnerOf>
void list_by_owner(int owners, int items, OwnerOf owner_of, std::vector<int>& begin, std::vector<int>& item) {
  begin.assign(static_cast<size_t>(owners) + 1, 0);
  for (int i = 0; i < items; ++i) ++begin[static_cast<size_t>(owner_of(i)) + 1];
  for (int o = 0; o < owners; ++o) begin[static_cast<size_t>(o) + 1] += begin[static_cast<size_t>(o)];
  item.resize(static_cast<size_t>(items));
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (int i = 0; i < items; ++i) item[static_cast<size_t>(fill[static_cast<size_t>(owner_of(i))]++)] = i;
}

void require_in_range(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("volume keeping: " + what);
}

// The coefficients of det[a + l p, b + l q, c + l r] in 1, l, l², l³.
Eigen::Vector4d cubic_terms(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c,
                            const Eigen::RowVector3d& p, const Eigen::RowVector3d& q, const Eigen::RowVector3d& r) {
  return {a.dot(b.cross(c)), p.dot(b.cross(c)) + a.dot(q.cross(c)) + a.dot(b.cross(r)),
          a.dot(q.cross(r)) + p.dot(b.cross(r)) + p.dot(q.cross(c)), p.dot(q.cross(r))};
}

// The faces grouped by the tets their corners lie in (one tet for most faces; a face across tets
// has up to 12 nodes): each group's nodes in increasing order.
struct FaceGroups {
  struct Group {
    std::array<int, 12> nodes;
    int count = 0;
    size_t first = 0;  // its first triple in the triples summed
    int triple_count() const { return count * (count - 1) * (count - 2) / 6; }
  };
  std::vector<Group> groups;
  std::vector<int> of_face;  // the group of each face
};

// A group's faces go through its node triples when these are no more than this many per face;
// else face by face (a coarse surface in a fine domain: a face's corners in three tets apart, 220
// triples for one face). 4 rather than 2: alike on a small part, and the faster global step on a
// million-face one (docs/history/speed.md).
constexpr int kTriplesPerFace = 4;

struct TetsHash {
  size_t operator()(const std::array<int, 3>& k) const {
    const auto u = [](int x) { return static_cast<unsigned long long>(static_cast<unsigned>(x)); };
    return std::hash<unsigned long long>()((u(k[0]) * 1000003ULL + u(k[1])) * 1000003ULL + u(k[2]));
  }
};

FaceGroups group_faces(const Embedding& e, const Triangles& F) {
  FaceGroups out;
  out.of_face.resize(static_cast<size_t>(F.rows()));
  std::vector<int> by_tet(static_cast<size_t>(e.vertex_tet.size() ? e.vertex_tet.maxCoeff() + 1 : 0), -1);
  std::unordered_map<std::array<int, 3>, int, TetsHash> across;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    std::array<int, 3> tets{e.vertex_tet(F(f, 0)), e.vertex_tet(F(f, 1)), e.vertex_tet(F(f, 2))};
    const bool one_tet = tets[0] == tets[1] && tets[1] == tets[2];
    std::sort(tets.begin(), tets.end());
    int& id = one_tet ? by_tet[static_cast<size_t>(tets[0])] : across.try_emplace(tets, -1).first->second;
    if (id < 0) {
      id = static_cast<int>(out.groups.size());
      FaceGroups::Group g;
      for (int k = 0; k < 3; ++k)
        for (int n = 0; n < 4; ++n) g.nodes[static_cast<size_t>(g.count++)] = e.vertex_nodes(F(f, k), n);
      std::sort(g.nodes.begin(), g.nodes.begin() + g.count);
      g.count = static_cast<int>(std::unique(g.nodes.begin(), g.nodes.begin() + g.count) - g.nodes.begin());
      out.groups.push_back(g);
    }
    out.of_face[static_cast<size_t>(f)] = id;
  }
  return out;
}

// Face f's minors added to its group's triples: the 3 by count matrix of its corners' weights on
// the group's nodes, and its minor at every three columns.
void add_minors(const Embedding& e, const Triangles& F, Eigen::Index f, const FaceGroups::Group& g,
                VolumeKeeping::Triple* triples) {
  Eigen::Matrix<double, 3, 12> w = Eigen::Matrix<double, 3, 12>::Zero();
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 4; ++k) {
      const auto at = std::lower_bound(g.nodes.begin(), g.nodes.begin() + g.count, e.vertex_nodes(F(f, r), k)) - g.nodes.begin();
      w(r, at) += e.vertex_bary(F(f, r), k);
    }
  for (int i = 0; i < g.count; ++i)
    for (int j = i + 1; j < g.count; ++j)
      for (int k = j + 1; k < g.count; ++k, ++triples) {
        Eigen::Matrix3d minor;
        minor << w.col(i), w.col(j), w.col(k);
        triples->coefficient += minor.determinant();
      }
}

// Every triple once (groups share them: the nodes of a tet's face are in the groups of both tets
// and of the faces across them), its coefficients summed in group order; in increasing order of
// nodes; none with a coefficient of zero. A counting sort by the first node, then each first
// node's few triples sorted on the threads.
std::vector<VolumeKeeping::Triple> merged(const std::vector<VolumeKeeping::Triple>& triples, Eigen::Index nodes) {
  std::vector<int> begin, order;
  list_by_owner(static_cast<int>(nodes), static_cast<int>(triples.size()),
                [&](int j) { return triples[static_cast<size_t>(j)].nodes[0]; }, begin, order);
  parallel_for(static_cast<int>(nodes), [&](int i) {
    std::sort(order.begin() + begin[static_cast<size_t>(i)], order.begin() + begin[static_cast<size_t>(i) + 1], [&](int x, int y) {
      return std::tie(triples[static_cast<size_t>(x)].nodes, x) < std::tie(triples[static_cast<size_t>(y)].nodes, y);
    });
  });
  std::vector<VolumeKeeping::Triple> out;
  for (int j : order) {
    const VolumeKeeping::Triple& t = triples[static_cast<size_t>(j)];
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
  // lie in the same tets share their nodes: each group's minors are summed over its faces in face
  // order, the groups on the threads (the same bits on any thread count).
  FaceGroups g = group_faces(e, F);
  std::vector<int> group_begin, faces_by_group;
  list_by_owner(static_cast<int>(g.groups.size()), static_cast<int>(F.rows()),
                [&](int f) { return g.of_face[static_cast<size_t>(f)]; }, group_begin, faces_by_group);
  std::vector<Triple> triples;
  std::vector<char> by_triples(g.groups.size());
  for (size_t k = 0; k < g.groups.size(); ++k) {
    FaceGroups::Group& group = g.groups[k];
    by_triples[k] = group.triple_count() <= kTriplesPerFace * (group_begin[k + 1] - group_begin[k]);
    if (!by_triples[k]) continue;
    group.first = triples.size();
    for (int i = 0; i < group.count; ++i)
      for (int j = i + 1; j < group.count; ++j)
        for (int l = j + 1; l < group.count; ++l) triples.push_back({{group.nodes[i], group.nodes[j], group.nodes[l]}, 0.0});
  }
  parallel_for(static_cast<int>(g.groups.size()), [&](int k) {
    const FaceGroups::Group& group = g.groups[static_cast<size_t>(k)];
    if (!by_triples[static_cast<size_t>(k)]) return;
    for (int j = group_begin[static_cast<size_t>(k)]; j < group_begin[static_cast<size_t>(k) + 1]; ++j)
      add_minors(e, F, faces_by_group[static_cast<size_t>(j)], group, &triples[group.first]);
  });
  triples_ = merged(triples, domain_vertices);
  // The other faces, in face order, each corner with its nodes and weights.
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (by_triples[static_cast<size_t>(g.of_face[static_cast<size_t>(f)])]) continue;
    Corners face;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 4; ++k) {
        face.nodes[static_cast<size_t>(r)][static_cast<size_t>(k)] = e.vertex_nodes(F(f, r), k);
        face.weights[static_cast<size_t>(r)][static_cast<size_t>(k)] = e.vertex_bary(F(f, r), k);
      }
    faces_.push_back(face);
  }
}

Eigen::RowVector3d VolumeKeeping::Corners::at(int r, const RowPoints& V) const {
  Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
  for (int k = 0; k < 4; ++k) x += weights[static_cast<size_t>(r)][static_cast<size_t>(k)] * V.row(nodes[static_cast<size_t>(r)][static_cast<size_t>(k)]);
  return x;
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
  for (const Corners& face : faces_) {
    const std::array<Eigen::RowVector3d, 3> x{face.at(0, P_), face.at(1, P_), face.at(2, P_)};
    for (int r = 0; r < 3; ++r) {
      const Eigen::RowVector3d g = x[static_cast<size_t>((r + 1) % 3)].cross(x[static_cast<size_t>((r + 2) % 3)]) / 6.0;
      for (int k = 0; k < 4; ++k)
        out.row(face.nodes[static_cast<size_t>(r)][static_cast<size_t>(k)]) += face.weights[static_cast<size_t>(r)][static_cast<size_t>(k)] * g;
    }
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
  for (const Corners& face : faces_)
    d += cubic_terms(face.at(0, P_), face.at(1, P_), face.at(2, P_), face.at(0, Q_), face.at(1, Q_), face.at(2, Q_));
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
