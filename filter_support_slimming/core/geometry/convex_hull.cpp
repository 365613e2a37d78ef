#include "core/geometry/convex_hull.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace slim {

namespace {

// Quickhull: every point not yet on the hull waits in the outside set of one facet it sees; the
// facet's farthest point is added next, the facets it sees are replaced by a cone from it over
// their horizon, and their waiting points move to the cone facets they see (or, tolerant, are
// dropped as inside).
class Quickhull {
 public:
  Quickhull(const Points& P, const ConvexHullOptions& o)
      : P_(P), eps_(o.eps), strict_(o.strict), next_outside_(static_cast<size_t>(P.rows()), -1),
        cone_start_(static_cast<size_t>(P.rows()), -1) {}

  bool build(ConvexHull& hull) {
    if (P_.rows() < 4) return false;
    facets_.reserve(static_cast<size_t>(8 * P_.rows()));  // ~6 per point are ever made
    if (!start_simplex()) return false;
    std::vector<int> pending{0, 1, 2, 3};
    while (!pending.empty()) {
      const int f = pending.back();
      pending.pop_back();
      if (!facets_[static_cast<size_t>(f)].alive || facets_[static_cast<size_t>(f)].outside < 0) continue;
      if (!add_farthest_point(f)) return false;
      pending.insert(pending.end(), cone_.begin(), cone_.end());
    }
    emit(hull);
    return true;
  }

 private:
  struct Facet {
    std::array<int, 3> v;     // counter-clockwise seen from outside
    std::array<int, 3> next;  // the facet across edge v[e] -> v[e + 1]
    Eigen::Vector3d normal;   // unit, outward
    double offset = 0.0;      // normal·v0
    double area2 = 0.0;       // |(v1 - v0) x (v2 - v0)|
    int outside = -1;         // first and last point of its outside set, a list through
    int outside_last = -1;    // next_outside_ in the order the points joined it
    int stamp = -1;           // 2 s: seen by the point of step s; 2 s + 1: not seen
    bool alive = true;
  };

  // What a facet says of a point: clearly outside, clearly not, or (strict) too close to tell.
  enum class Side { Outside, Inside, Unsure };

  Eigen::Vector3d point(int i) const { return P_.row(i).transpose(); }
  double height(const Facet& f, int q) const { return f.normal.dot(point(q)) - f.offset; }
  Side side(const Facet& f, int q) const {
    const double h = height(f, q);
    if (strict_) return std::abs(h) * f.area2 <= eps_ ? Side::Unsure : (h > 0.0 ? Side::Outside : Side::Inside);
    return h > eps_ ? Side::Outside : Side::Inside;
  }

  // False when the triangle is too thin to have a trustworthy normal.
  bool add_facet(int a, int b, int c) {
    Facet f;
    f.v = {a, b, c};
    f.next = {-1, -1, -1};
    const Eigen::Vector3d n = (point(b) - point(a)).cross(point(c) - point(a));
    f.area2 = n.norm();
    if (!(f.area2 > (strict_ ? 0.0 : eps_ * (point(b) - point(a)).norm()))) return false;
    f.normal = n / f.area2;
    f.offset = f.normal.dot(point(a));
    facets_.push_back(f);
    return true;
  }

  // q joins the outside set of the first of `candidates` it is clearly outside of. Seeing none, it
  // is inside: dropped when tolerant; strict, every point is a vertex, so that is a degeneracy.
  bool assign(int q, const std::vector<int>& candidates) {
    for (int f : candidates) {
      Facet& facet = facets_[static_cast<size_t>(f)];
      const Side s = side(facet, q);
      if (s == Side::Unsure) return false;
      if (s == Side::Outside) {
        next_outside_[static_cast<size_t>(q)] = -1;
        if (facet.outside < 0) facet.outside = q;
        else next_outside_[static_cast<size_t>(facet.outside_last)] = q;
        facet.outside_last = q;
        return true;
      }
    }
    return !strict_;
  }

  // The widest pair among the points extreme along the axes, then the farthest point from
  // their line, then from their plane.
  bool start_simplex();
  bool add_farthest_point(int first);
  bool link_cone(int q, const std::vector<int>& visible);
  void emit(ConvexHull& hull) const;

  const Points& P_;
  const double eps_;
  const bool strict_;
  std::vector<Facet> facets_;
  std::vector<int> next_outside_;  // per point: the next one in the same outside set
  std::vector<int> cone_start_;    // per point: the cone facet whose horizon edge starts there
  std::vector<int> visible_, cone_;  // scratch of add_farthest_point, kept to reuse their memory
  int step_ = 0;
};

bool Quickhull::start_simplex() {
  const int n = static_cast<int>(P_.rows());
  std::array<int, 6> extreme{};
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Index lo = 0, hi = 0;
    P_.col(axis).minCoeff(&lo);
    P_.col(axis).maxCoeff(&hi);
    extreme[static_cast<size_t>(2 * axis)] = static_cast<int>(lo);
    extreme[static_cast<size_t>(2 * axis + 1)] = static_cast<int>(hi);
  }
  int a = extreme[0], b = extreme[1];
  double widest = -1.0;
  for (int i : extreme)
    for (int j : extreme)
      if ((point(i) - point(j)).squaredNorm() > widest) widest = (point(i) - point(j)).squaredNorm(), a = i, b = j;
  auto farthest = [&](auto&& distance) {
    int best = 0;
    double best_distance = -1.0;
    for (int i = 0; i < n; ++i) {
      const double value = distance(point(i));
      if (value > best_distance) best = i, best_distance = value;
    }
    return std::make_pair(best, best_distance);
  };
  const Eigen::Vector3d ab = (point(b) - point(a)).normalized();
  const auto [c, off_line] = farthest([&](const Eigen::Vector3d& x) { return ab.cross(x - point(a)).norm(); });
  if (!(off_line > eps_)) return false;
  const Eigen::Vector3d plane = ab.cross(point(c) - point(a)).normalized();
  const auto [d, off_plane] = farthest([&](const Eigen::Vector3d& x) { return std::abs(plane.dot(x - point(a))); });
  if (!(off_plane > eps_)) return false;
  const bool d_above_abc = plane.dot(point(d) - point(a)) > 0.0;
  const std::array<std::array<int, 3>, 4> faces =
      d_above_abc ? std::array<std::array<int, 3>, 4>{{{a, c, b}, {a, b, d}, {b, c, d}, {c, a, d}}}
                  : std::array<std::array<int, 3>, 4>{{{a, b, c}, {a, d, b}, {b, d, c}, {c, d, a}}};
  for (const auto& f : faces)
    if (!add_facet(f[0], f[1], f[2])) return false;
  for (Facet& f : facets_)
    for (int e = 0; e < 3; ++e)
      for (int g = 0; g < 4; ++g)
        for (int k = 0; k < 3; ++k)
          if (facets_[static_cast<size_t>(g)].v[static_cast<size_t>(k)] == f.v[static_cast<size_t>((e + 1) % 3)] &&
              facets_[static_cast<size_t>(g)].v[static_cast<size_t>((k + 1) % 3)] == f.v[static_cast<size_t>(e)])
            f.next[static_cast<size_t>(e)] = g;
  const std::vector<int> all = {0, 1, 2, 3};
  for (int q = 0; q < n; ++q)
    if (q != a && q != b && q != c && q != d && !assign(q, all)) return false;
  return true;
}

bool Quickhull::add_farthest_point(int first) {
  ++step_;
  int q = -1;
  double q_height = -1.0;
  for (int p = facets_[static_cast<size_t>(first)].outside; p >= 0; p = next_outside_[static_cast<size_t>(p)]) {
    const double h = height(facets_[static_cast<size_t>(first)], p);
    if (h > q_height) q = p, q_height = h;
  }
  // The facets q sees: a connected patch around `first`.
  std::vector<int>& visible = visible_;
  visible.assign(1, first);
  facets_[static_cast<size_t>(first)].stamp = 2 * step_;
  for (size_t k = 0; k < visible.size(); ++k) {
    for (int e = 0; e < 3; ++e) {
      const int g = facets_[static_cast<size_t>(visible[k])].next[static_cast<size_t>(e)];
      Facet& neighbour = facets_[static_cast<size_t>(g)];
      if (neighbour.stamp == 2 * step_ || neighbour.stamp == 2 * step_ + 1) continue;
      const Side s = side(neighbour, q);
      if (s == Side::Unsure) return false;
      neighbour.stamp = 2 * step_ + (s == Side::Outside ? 0 : 1);
      if (s == Side::Outside) visible.push_back(g);
    }
  }
  if (!link_cone(q, visible)) return false;
  // The points waiting on the replaced facets move to the cone facets they see.
  for (int f : visible) {
    Facet& gone = facets_[static_cast<size_t>(f)];
    gone.alive = false;
    for (int p = gone.outside, after; p >= 0; p = after) {
      after = next_outside_[static_cast<size_t>(p)];
      if (p != q && !assign(p, cone_)) return false;
    }
    gone.outside = gone.outside_last = -1;
  }
  return true;
}

// A cone of new facets from q over the horizon of `visible`, which must be one simple loop.
bool Quickhull::link_cone(int q, const std::vector<int>& visible) {
  std::vector<int>& cone = cone_;
  cone.clear();
  for (int f : visible) {
    for (int e = 0; e < 3; ++e) {
      const int g = facets_[static_cast<size_t>(f)].next[static_cast<size_t>(e)];
      if (facets_[static_cast<size_t>(g)].stamp != 2 * step_ + 1) continue;
      const int a = facets_[static_cast<size_t>(f)].v[static_cast<size_t>(e)];
      const int b = facets_[static_cast<size_t>(f)].v[static_cast<size_t>((e + 1) % 3)];
      if (cone_start_[static_cast<size_t>(a)] >= 0) return false;
      if (!add_facet(a, b, q)) return false;
      const int added = static_cast<int>(facets_.size()) - 1;
      cone.push_back(added);
      cone_start_[static_cast<size_t>(a)] = added;
      facets_[static_cast<size_t>(added)].next[0] = g;
      Facet& outer = facets_[static_cast<size_t>(g)];
      for (int k = 0; k < 3; ++k)
        if (outer.v[static_cast<size_t>(k)] == b && outer.v[static_cast<size_t>((k + 1) % 3)] == a)
          outer.next[static_cast<size_t>(k)] = added;
    }
  }
  bool closed = true;
  for (int added : cone) {
    const int b = facets_[static_cast<size_t>(added)].v[1];
    const int after = cone_start_[static_cast<size_t>(b)];
    if (after < 0) {
      closed = false;
      continue;
    }
    facets_[static_cast<size_t>(added)].next[1] = after;
    facets_[static_cast<size_t>(after)].next[2] = added;
  }
  for (int added : cone) cone_start_[static_cast<size_t>(facets_[static_cast<size_t>(added)].v[0])] = -1;
  return closed;
}

void Quickhull::emit(ConvexHull& hull) const {
  hull = ConvexHull{};
  std::vector<bool> used(static_cast<size_t>(P_.rows()), false);
  std::vector<int> renumbered(facets_.size(), -1);
  for (size_t k = 0; k < facets_.size(); ++k) {
    if (!facets_[k].alive) continue;
    renumbered[k] = static_cast<int>(hull.facets.size());
    hull.facets.push_back(facets_[k].v);
    for (int v : facets_[k].v) used[static_cast<size_t>(v)] = true;
  }
  for (const Facet& f : facets_)
    if (f.alive)
      hull.neighbours.push_back({renumbered[static_cast<size_t>(f.next[0])], renumbered[static_cast<size_t>(f.next[1])],
                                 renumbered[static_cast<size_t>(f.next[2])]});
  const Eigen::Index h = static_cast<Eigen::Index>(hull.facets.size());
  hull.normals.resize(h, 3);
  hull.areas.resize(h);
  Eigen::Index row = 0;
  for (const Facet& f : facets_) {
    if (!f.alive) continue;
    hull.normals.row(row) = f.normal.transpose();
    hull.areas(row) = 0.5 * (point(f.v[1]) - point(f.v[0])).cross(point(f.v[2]) - point(f.v[0])).norm();
    ++row;
  }
  for (int i = 0; i < static_cast<int>(used.size()); ++i)
    if (used[static_cast<size_t>(i)]) hull.vertices.push_back(i);
}

}  // namespace

bool convex_hull(const Points& P, const ConvexHullOptions& options, ConvexHull& hull) {
  hull = ConvexHull{};
  if (!P.allFinite() || !(options.eps >= 0.0)) return false;
  Quickhull builder(P, options);
  if (builder.build(hull)) return true;
  hull = ConvexHull{};
  return false;
}

bool convex_hull(const Points& P, double eps, ConvexHull& hull) {
  ConvexHullOptions options;
  options.eps = eps;
  return convex_hull(P, options, hull);
}

std::vector<HullEdge> hull_edges(const ConvexHull& hull) {
  std::vector<HullEdge> edges;
  edges.reserve(3 * hull.facets.size() / 2);
  for (size_t f = 0; f < hull.facets.size(); ++f) {
    const std::array<int, 3>& v = hull.facets[f];
    for (size_t e = 0; e < 3; ++e) {
      const int i = v[e], j = v[(e + 1) % 3];
      if (i > j) continue;  // each edge once
      const std::array<int, 3>& g = hull.facets[static_cast<size_t>(hull.neighbours[f][e])];
      const int l = g[0] != i && g[0] != j ? g[0] : (g[1] != i && g[1] != j ? g[1] : g[2]);
      edges.push_back({i, j, v[(e + 2) % 3], l});
    }
  }
  return edges;
}

}  // namespace slim
