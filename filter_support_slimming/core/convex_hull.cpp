#include "core/convex_hull.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace slim {

namespace {

// Quickhull: every point not yet on the hull waits in the outside set of one facet it sees; the
// facet's farthest point is added next, the facets it sees are replaced by a cone from it over
// their horizon, and their waiting points move to the cone facets they see (or are dropped as
// inside). Taking the farthest point first keeps the facets large and well shaped, which is what
// makes the eps tests trustworthy.
class Quickhull {
 public:
  Quickhull(const Points& P, double eps) : P_(P), eps_(eps), cone_start_(static_cast<size_t>(P.rows()), -1) {}

  bool build(ConvexHull& hull) {
    if (P_.rows() < 4 || !start_simplex()) return false;
    std::vector<int> pending;
    for (int f = 0; f < 4; ++f) pending.push_back(f);
    while (!pending.empty()) {
      const int f = pending.back();
      pending.pop_back();
      if (!facets_[static_cast<size_t>(f)].alive || facets_[static_cast<size_t>(f)].outside.empty()) continue;
      std::vector<int> cone;
      if (!add_farthest_point(f, cone)) return false;
      pending.insert(pending.end(), cone.begin(), cone.end());
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
    std::vector<int> outside;
    int stamp = -1;           // 2 s: seen by the point of step s; 2 s + 1: not seen
    bool alive = true;
  };

  Eigen::Vector3d point(int i) const { return P_.row(i).transpose(); }
  double height(const Facet& f, int q) const { return f.normal.dot(point(q)) - f.offset; }

  // False when the triangle is too thin to have a trustworthy normal.
  bool add_facet(int a, int b, int c) {
    Facet f;
    f.v = {a, b, c};
    f.next = {-1, -1, -1};
    const Eigen::Vector3d n = (point(b) - point(a)).cross(point(c) - point(a));
    const double length = n.norm();
    if (!(length > eps_ * (point(b) - point(a)).norm())) return false;
    f.normal = n / length;
    f.offset = f.normal.dot(point(a));
    facets_.push_back(std::move(f));
    return true;
  }

  // The first of `candidates` that q is clearly outside of gets q; none: q is inside, dropped.
  void assign(int q, const std::vector<int>& candidates) {
    for (int f : candidates) {
      if (height(facets_[static_cast<size_t>(f)], q) > eps_) {
        facets_[static_cast<size_t>(f)].outside.push_back(q);
        return;
      }
    }
  }

  bool start_simplex() {
    const int n = static_cast<int>(P_.rows());
    // The widest pair among the points extreme along the axes, then the farthest point from
    // their line, then from their plane.
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
      if (q != a && q != b && q != c && q != d) assign(q, all);
    return true;
  }

  bool add_farthest_point(int first, std::vector<int>& cone) {
    ++step_;
    int q = -1;
    double q_height = -1.0;
    for (int p : facets_[static_cast<size_t>(first)].outside) {
      const double h = height(facets_[static_cast<size_t>(first)], p);
      if (h > q_height) q = p, q_height = h;
    }
    // The facets q sees: a connected patch around `first`.
    std::vector<int> visible{first};
    facets_[static_cast<size_t>(first)].stamp = 2 * step_;
    for (size_t k = 0; k < visible.size(); ++k) {
      for (int e = 0; e < 3; ++e) {
        const int g = facets_[static_cast<size_t>(visible[k])].next[static_cast<size_t>(e)];
        Facet& neighbour = facets_[static_cast<size_t>(g)];
        if (neighbour.stamp == 2 * step_ || neighbour.stamp == 2 * step_ + 1) continue;
        const bool sees = height(neighbour, q) > eps_;
        neighbour.stamp = 2 * step_ + (sees ? 0 : 1);
        if (sees) visible.push_back(g);
      }
    }
    // A cone of new facets from q over the horizon, which must be one simple loop.
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
    if (!closed) return false;
    // The points waiting on the replaced facets move to the cone facets they see.
    for (int f : visible) {
      Facet& gone = facets_[static_cast<size_t>(f)];
      gone.alive = false;
      std::vector<int> waiting;
      waiting.swap(gone.outside);
      for (int p : waiting)
        if (p != q) assign(p, cone);
    }
    return true;
  }

  void emit(ConvexHull& hull) const {
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

  const Points& P_;
  const double eps_;
  std::vector<Facet> facets_;
  std::vector<int> cone_start_;  // per point: the cone facet whose horizon edge starts there
  int step_ = 0;
};

}  // namespace

bool convex_hull(const Points& P, double eps, ConvexHull& hull) {
  hull = ConvexHull{};
  if (!P.allFinite() || !(eps >= 0.0)) return false;
  Quickhull builder(P, eps);
  if (builder.build(hull)) return true;
  hull = ConvexHull{};
  return false;
}

}  // namespace slim
