#include "core/geometry/shape_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "core/platform/parallel_for.h"
#include "core/utilities/weighted_quantile.h"

namespace slim {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

// One directed edge of a face: (lower vertex, higher vertex), the face, and whether the face runs
// from the lower to the higher vertex.
struct HalfEdge {
  int lo, hi, face;
  bool forward;
};

// Sorted by (lo, hi, face): a counting sort by the lower vertex, then each vertex's few half-edges
// (one std::sort of them all would be most of a crease meter's set-up on a large part).
std::vector<HalfEdge> sorted_half_edges(const Triangles& F) {
  const int vertices = F.size() > 0 ? F.maxCoeff() + 1 : 0;
  std::vector<int> begin(static_cast<size_t>(vertices) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) ++begin[static_cast<size_t>(std::min(a, b)) + 1];
    }
  for (int v = 0; v < vertices; ++v) begin[static_cast<size_t>(v) + 1] += begin[static_cast<size_t>(v)];
  std::vector<HalfEdge> h(static_cast<size_t>(begin.back()));
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)  // faces ascending: each vertex's list is in face order
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      if (a != b) h[static_cast<size_t>(fill[static_cast<size_t>(std::min(a, b))]++)] = {std::min(a, b), std::max(a, b), static_cast<int>(f), a < b};
    }
  for (int v = 0; v < vertices; ++v)
    std::stable_sort(h.begin() + begin[static_cast<size_t>(v)], h.begin() + begin[static_cast<size_t>(v) + 1],
                     [](const HalfEdge& x, const HalfEdge& y) { return x.hi < y.hi; });
  return h;
}

// Signed angle (degrees) from normal n0 to normal n1 about the edge direction e (unit), e running
// the way face 0 runs along it: positive where the surface is convex.
double signed_dihedral(const Eigen::Vector3d& n0, const Eigen::Vector3d& n1, const Eigen::Vector3d& e) {
  return std::atan2(n0.cross(n1).dot(e), n0.dot(n1)) * kDegrees;
}

// The interior manifold edges of a topology (faces F), ignoring geometry: pairs of half-edges.
struct EdgePair {
  int v0, v1, f0, f1;  // f0 runs v0 -> v1
};

std::vector<EdgePair> interior_manifold_edges(const Triangles& F) {
  const std::vector<HalfEdge> h = sorted_half_edges(F);
  std::vector<EdgePair> out;
  for (size_t i = 0; i < h.size();) {
    size_t j = i;
    while (j < h.size() && h[j].lo == h[i].lo && h[j].hi == h[i].hi) ++j;
    if (j - i == 2 && h[i].forward != h[i + 1].forward && h[i].face != h[i + 1].face) {
      const HalfEdge& fwd = h[i].forward ? h[i] : h[i + 1];
      const HalfEdge& bwd = h[i].forward ? h[i + 1] : h[i];
      out.push_back({fwd.lo, fwd.hi, fwd.face, bwd.face});
    }
    i = j;
  }
  return out;
}

double edge_angle(const Surface& s, const Points& normals, const EdgePair& e) {
  const Eigen::Vector3d dir = (s.V.row(e.v1) - s.V.row(e.v0)).transpose().normalized();
  return signed_dihedral(normals.row(e.f0).transpose(), normals.row(e.f1).transpose(), dir);
}

bool has_area(const Points& normals, int f) { return normals.row(f).squaredNorm() > 0.0; }

void require_same_vertex_count(Eigen::Index input, Eigen::Index result) {
  if (input != result)
    throw std::invalid_argument("shape change: the input has " + std::to_string(input) + " vertices, the result " +
                                std::to_string(result) + ": not the same mesh");
}

}  // namespace

std::vector<DihedralEdge> dihedral_edges(const Surface& s) {
  check_surface(s);
  const Points n = face_normals(s);
  const std::vector<EdgePair> pairs = interior_manifold_edges(s.F);
  // The angles on the threads (an atan2 each), the edges without area dropped after, in order.
  std::vector<DihedralEdge> all(pairs.size());
  const auto count = static_cast<long>(pairs.size());
#pragma omp parallel for schedule(static) if (count > 65536)
  for (long i = 0; i < count; ++i) {
    const EdgePair& e = pairs[static_cast<size_t>(i)];
    const bool area = has_area(n, e.f0) && has_area(n, e.f1);
    all[static_cast<size_t>(i)] = {e.v0, e.v1, area ? e.f0 : -1, e.f1, area ? edge_angle(s, n, e) : 0.0};
  }
  std::vector<DihedralEdge> out;
  out.reserve(all.size());
  for (const DihedralEdge& e : all)
    if (e.f0 >= 0) out.push_back(e);
  return out;
}

CreaseMeter::CreaseMeter(const Surface& input, const ShapeChangeOptions& options)
    : F_(input.F), vertices_(input.V.rows()), options_(options), edges_(dihedral_edges(input)),
      volume_input_(signed_volume(input)) {
  if (!(options.crease_threshold_deg >= 0.0 && options.crease_threshold_deg < 180.0))
    throw std::invalid_argument("shape change: the crease threshold must lie in [0, 180) degrees");
  const auto count = static_cast<long>(edges_.size());
  length_.resize(edges_.size());
  cos_in_.resize(edges_.size());
  sin_in_.resize(edges_.size());
#pragma omp parallel for schedule(static) if (count > 65536)
  for (long k = 0; k < count; ++k) {
    const DihedralEdge& e = edges_[static_cast<size_t>(k)];
    length_[static_cast<size_t>(k)] = (input.V.row(e.v1) - input.V.row(e.v0)).norm();
    cos_in_[static_cast<size_t>(k)] = std::cos(e.angle_deg / kDegrees);
    sin_in_[static_cast<size_t>(k)] = std::sin(e.angle_deg / kDegrees);
  }
}

void CreaseMeter::changes(const Surface& result, std::vector<double>& change, std::vector<char>& measured) const {
  require_same_vertex_count(vertices_, result.V.rows());
  const Points n = face_normals(result);
  change.assign(edges_.size(), 0.0);
  measured.assign(edges_.size(), 0);
  parallel_for(static_cast<int>(edges_.size()), [&](int k) {
    const DihedralEdge& e = edges_[static_cast<size_t>(k)];
    if (!has_area(n, e.f0) || !has_area(n, e.f1)) return;
    const double angle = edge_angle(result, n, EdgePair{e.v0, e.v1, e.f0, e.f1});
    change[static_cast<size_t>(k)] = std::abs(std::remainder(angle - e.angle_deg, 360.0));
    measured[static_cast<size_t>(k)] = 1;
  });
}

void CreaseMeter::measure(const Points& V, ShapeChange& out) const {
  std::vector<double> change, length;
  std::vector<char> measured;
  const Surface result{V, F_};
  changes(result, change, measured);
  out.volume_input = volume_input_;
  out.volume_result = signed_volume(result);
  out.volume_defined = out.volume_input != 0.0 && std::isfinite(out.volume_input);
  out.volume_change_pct = out.volume_defined ? 100.0 * (out.volume_result / out.volume_input - 1.0) : 0.0;
  double creased = 0.0, total = 0.0;
  out.max_crease_deg = 0.0;
  for (size_t k = 0; k < edges_.size(); ++k) {
    if (!measured[k]) continue;
    change[length.size()] = change[k];
    length.push_back(length_[k]);
    total += length_[k];
    if (change[k] > options_.crease_threshold_deg) creased += length_[k];
    out.max_crease_deg = std::max(out.max_crease_deg, change[k]);
  }
  change.resize(length.size());
  out.interior_edges = static_cast<Eigen::Index>(length.size());
  out.crease_share_pct = total > 0.0 ? 100.0 * creased / total : 0.0;
  out.crease_p99_deg = weighted_quantile(change, length, 0.99);
}

double CreaseMeter::share_pct(const Points& V) const {
  require_same_vertex_count(vertices_, V.rows());
  // As measure(), without the percentile's sort, and without an angle: the change exceeds the
  // threshold T exactly when the cosine of the difference of the two angles, from their sines
  // and cosines, is below cos T (the change lies in [0, 180]). Nothing is normalised: the faces'
  // cross products N0, N1 and the edge E give the cosine and sine both scaled by |N0| |N1| |E|,
  // which the comparison divides out.
  // Plain static loops (no exception can leave these bodies): parallel_for's per-item guard
  // kept them from vectorising, and glibc's hypot cost as much as the rest of an edge. The faces'
  // cross products by rows (an edge reads two far apart: one cache line each so, not three), in a
  // buffer kept from call to call (a fresh one costs a page fault every 4 kB).
  const Eigen::Index nf = F_.rows();
  RowPoints& cross = cross_;
  cross.resize(nf, 3);
#pragma omp parallel for schedule(static) if (nf > 65536)
  for (Eigen::Index f = 0; f < nf; ++f) cross.row(f) = face_cross(V, F_, f).transpose();
  const double cos_threshold = std::cos(options_.crease_threshold_deg / kDegrees);
  const auto edges = static_cast<Eigen::Index>(edges_.size());
  std::vector<char>& state = state_;  // 0 not measured, 1 measured, 2 creased
  state.resize(edges_.size());
#pragma omp parallel for schedule(static) if (edges > 65536)
  for (Eigen::Index k = 0; k < edges; ++k) {
    const DihedralEdge& e = edges_[static_cast<size_t>(k)];
    const Eigen::Vector3d n0 = cross.row(e.f0).transpose(), n1 = cross.row(e.f1).transpose();
    const Eigen::Vector3d edge = (V.row(e.v1) - V.row(e.v0)).transpose();
    const double length = edge.norm();
    const double cos_new = n0.dot(n1) * length, sin_new = n0.cross(n1).dot(edge);
    const double scale = std::sqrt(cos_new * cos_new + sin_new * sin_new);
    const double cos_change = cos_new * cos_in_[static_cast<size_t>(k)] + sin_new * sin_in_[static_cast<size_t>(k)];
    const bool area = n0.squaredNorm() > 0.0 && n1.squaredNorm() > 0.0 && std::isfinite(scale);
    state[static_cast<size_t>(k)] = !area || !(scale > 0.0) ? 0 : cos_change < cos_threshold * scale ? 2 : 1;
  }
  // The sums in edge order, as measure() makes them (an unmeasured edge adds 0: no bit changes).
  double creased = 0.0, total = 0.0;
  for (size_t k = 0; k < edges_.size(); ++k) {
    total += state[k] ? length_[k] : 0.0;
    creased += state[k] == 2 ? length_[k] : 0.0;
  }
  return total > 0.0 ? 100.0 * creased / total : 0.0;
}

ShapeChange shape_change(const Surface& input, const Surface& result, const ShapeChangeOptions& options) {
  check_surface(input);
  check_surface(result);
  require_same_vertex_count(input.V.rows(), result.V.rows());
  if (input.F.rows() != result.F.rows() || input.F != result.F)
    throw std::invalid_argument("shape change: the input and the result do not have the same faces");
  ShapeChange out;
  CreaseMeter(input, options).measure(result.V, out);
  return out;
}

}  // namespace slim
