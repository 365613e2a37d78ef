#include "core/geometry/surface_intersections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "core/geometry/uniform_grid.h"

namespace slim {

namespace {

using V3 = Eigen::Vector3d;

// ---- geometric predicates (plain double: exact zeros come from exactly coplanar data) --------

int sign(double x) { return (x > 0) - (x < 0); }

int orient3d(const V3& a, const V3& b, const V3& c, const V3& d) { return sign((b - a).dot((c - a).cross(d - a))); }

// The 2D plane that drops the dominant axis of n.
struct Plane2 {
  int u, v;
  explicit Plane2(const V3& n) {
    int drop = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(n(a)) > std::abs(n(drop))) drop = a;
    u = (drop + 1) % 3;
    v = (drop + 2) % 3;
  }
  int orient(const V3& a, const V3& b, const V3& c) const {
    return sign((b(u) - a(u)) * (c(v) - a(v)) - (b(v) - a(v)) * (c(u) - a(u)));
  }
  bool on_segment(const V3& p, const V3& a, const V3& b) const {  // p collinear with a, b
    return std::min(a(u), b(u)) <= p(u) && p(u) <= std::max(a(u), b(u)) && std::min(a(v), b(v)) <= p(v) &&
           p(v) <= std::max(a(v), b(v));
  }
  bool segments_meet(const V3& p, const V3& q, const V3& a, const V3& b) const {
    const int o1 = orient(p, q, a), o2 = orient(p, q, b), o3 = orient(a, b, p), o4 = orient(a, b, q);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && on_segment(a, p, q)) || (o2 == 0 && on_segment(b, p, q)) || (o3 == 0 && on_segment(p, a, b)) ||
           (o4 == 0 && on_segment(q, a, b));
  }
  bool in_triangle(const V3& p, const V3& a, const V3& b, const V3& c) const {
    const int s1 = orient(a, b, p), s2 = orient(b, c, p), s3 = orient(c, a, p);
    return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
  }
  bool segment_meets_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) const {
    return in_triangle(p, a, b, c) || segments_meet(p, q, a, b) || segments_meet(p, q, b, c) || segments_meet(p, q, c, a);
  }
};

// Closed segment pq against closed triangle abc.
bool segment_meets_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp == sq && sp != 0) return false;
  if (sp == 0 && sq == 0) return Plane2((b - a).cross(c - a)).segment_meets_triangle(p, q, a, b, c);
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  return !((s1 < 0 || s2 < 0 || s3 < 0) && (s1 > 0 || s2 > 0 || s3 > 0));
}

using Tri = std::array<V3, 3>;

// Two closed triangles with no common vertex.
bool triangles_meet(const Tri& A, const Tri& B) {
  std::array<int, 3> sa{}, sb{};
  for (size_t i = 0; i < 3; ++i) {
    sa[i] = orient3d(B[0], B[1], B[2], A[i]);
    sb[i] = orient3d(A[0], A[1], A[2], B[i]);
  }
  auto one_side = [](const std::array<int, 3>& s) { return (s[0] == s[1] && s[1] == s[2] && s[0] != 0); };
  if (one_side(sa) || one_side(sb)) return false;
  if (sa == std::array<int, 3>{0, 0, 0}) {  // coplanar
    const Plane2 P((A[1] - A[0]).cross(A[2] - A[0]));
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        if (P.segments_meet(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3])) return true;
    return P.in_triangle(A[0], B[0], B[1], B[2]) || P.in_triangle(B[0], A[0], A[1], A[2]);
  }
  // Not coplanar: the intersection, if any, ends on an edge of one of them.
  for (size_t i = 0; i < 3; ++i)
    if (segment_meets_triangle(A[i], A[(i + 1) % 3], B[0], B[1], B[2]) ||
        segment_meets_triangle(B[i], B[(i + 1) % 3], A[0], A[1], A[2]))
      return true;
  return false;
}

// Ray v->x inside the closed wedge of triangle (v, a1, a2) at v (x in its plane).
bool in_wedge(const V3& v, const V3& a1, const V3& a2, const V3& x) {
  const V3 n = (a1 - v).cross(a2 - v), u = x - v;
  return (a1 - v).cross(u).dot(n) >= 0 && u.cross(a2 - v).dot(n) >= 0;
}

// Triangles (v, a1, a2) and (v, b1, b2) that share only v: do they meet anywhere else?
bool fan_triangles_meet(const V3& v, const V3& a1, const V3& a2, const V3& b1, const V3& b2) {
  if (segment_meets_triangle(a1, a2, v, b1, b2) || segment_meets_triangle(b1, b2, v, a1, a2)) return true;
  for (const V3* x : {&b1, &b2})
    if (orient3d(v, a1, a2, *x) == 0 && in_wedge(v, a1, a2, *x)) return true;
  for (const V3* x : {&a1, &a2})
    if (orient3d(v, b1, b2, *x) == 0 && in_wedge(v, b1, b2, *x)) return true;
  return false;
}

// Faces f and g (distinct) meet where they should not.
bool faces_meet_improperly(const Surface& s, Eigen::Index f, Eigen::Index g) {
  std::array<int, 3> F{s.F(f, 0), s.F(f, 1), s.F(f, 2)}, G{s.F(g, 0), s.F(g, 1), s.F(g, 2)};
  int shared = 0;
  std::array<int, 3> at_f{-1, -1, -1};  // at_f[i]: the corner of G equal to corner i of F
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      if (F[i] == G[j]) {
        at_f[i] = static_cast<int>(j);
        ++shared;
      }
  auto P = [&](int v) -> V3 { return s.V.row(v).transpose(); };
  if (shared == 0) return triangles_meet({P(F[0]), P(F[1]), P(F[2])}, {P(G[0]), P(G[1]), P(G[2])});
  if (shared >= 3) return true;  // the same triangle twice
  if (shared == 1) {
    const size_t i = static_cast<size_t>(std::find_if(at_f.begin(), at_f.end(), [](int j) { return j >= 0; }) - at_f.begin());
    const size_t j = static_cast<size_t>(at_f[i]);
    return fan_triangles_meet(P(F[i]), P(F[(i + 1) % 3]), P(F[(i + 2) % 3]), P(G[(j + 1) % 3]), P(G[(j + 2) % 3]));
  }
  // Two shared vertices: an edge u-v. Only a fold (coplanar, both on the same side) is wrong.
  size_t lone_f = 0, lone_g = 0;
  for (size_t i = 0; i < 3; ++i)
    if (at_f[i] < 0) lone_f = i;
  for (size_t j = 0; j < 3; ++j)
    if (std::find(at_f.begin(), at_f.end(), static_cast<int>(j)) == at_f.end()) lone_g = j;
  const V3 u = P(F[(lone_f + 1) % 3]), v = P(F[(lone_f + 2) % 3]), a = P(F[lone_f]), b = P(G[lone_g]);
  if (orient3d(u, v, a, b) != 0) return false;
  return (v - u).cross(a - u).dot((v - u).cross(b - u)) > 0;
}

}  // namespace

bool first_self_intersection(const Surface& s, int& first, int& second) {
  const Eigen::Index nf = s.F.rows();
  if (nf == 0) return false;
  Points lo(nf, 3), hi(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f) {
    lo.row(f) = s.V.row(s.F(f, 0)).cwiseMin(s.V.row(s.F(f, 1))).cwiseMin(s.V.row(s.F(f, 2)));
    hi.row(f) = s.V.row(s.F(f, 0)).cwiseMax(s.V.row(s.F(f, 1))).cwiseMax(s.V.row(s.F(f, 2)));
  }
  const Eigen::Vector3d glo = lo.colwise().minCoeff().transpose(), ghi = hi.colwise().maxCoeff().transpose();
  const double diag = (ghi - glo).norm();
  const Eigen::Vector3d extent = (ghi - glo) + Eigen::Vector3d::Constant(1e-9 * diag + 1e-300);
  const double side = std::cbrt(extent.prod() / static_cast<double>(nf));
  Eigen::Vector3i dims;
  for (int a = 0; a < 3; ++a) dims(a) = std::clamp(static_cast<int>(std::ceil(extent(a) / side)), 1, 256);
  UniformGrid grid(glo, extent.cwiseQuotient(dims.cast<double>()), dims);
  grid.fill(static_cast<int>(nf), [&](int f, Eigen::Vector3d& a, Eigen::Vector3d& b) {
    a = lo.row(f).transpose();
    b = hi.row(f).transpose();
  });
  // The lexicographically smallest offending pair, whatever the thread count.
  std::int64_t worst = std::numeric_limits<std::int64_t>::max();
  const std::int64_t n64 = nf;
  const std::int64_t ncells = static_cast<std::int64_t>(grid.cell_count());
#pragma omp parallel for schedule(dynamic, 64) if (nf > 8192)
  for (std::int64_t c = 0; c < ncells; ++c) {
    const UniformGrid::Items items = grid.items(static_cast<size_t>(c));
    for (const int* x = items.begin(); x != items.end(); ++x)
      for (const int* y = x + 1; y != items.end(); ++y) {
        const int f = *x, g = *y;
        if ((lo.row(f).array() > hi.row(g).array()).any() || (lo.row(g).array() > hi.row(f).array()).any()) continue;
        if (grid.index(grid.cell_of(lo.row(f).cwiseMax(lo.row(g)).transpose())) != static_cast<size_t>(c)) continue;
        if (!faces_meet_improperly(s, f, g)) continue;
        const std::int64_t key = std::min(f, g) * n64 + std::max(f, g);
#pragma omp critical(slim_self_intersection)
        worst = std::min(worst, key);
      }
  }
  if (worst == std::numeric_limits<std::int64_t>::max()) return false;
  first = static_cast<int>(worst / n64);
  second = static_cast<int>(worst % n64);
  return true;
}

}  // namespace slim
