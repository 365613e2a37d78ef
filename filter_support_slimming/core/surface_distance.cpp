#include "core/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/face_box_tree.h"

namespace slim {

namespace {

Eigen::Vector3d corner(const Surface& s, Eigen::Index f, int k) { return s.V.row(s.F(f, k)).transpose(); }

// The samples of a surface: the vertices that faces use (a vertex of no face is no part of the
// surface, and the moved search's bound, how far a sample moved, holds only on the surface), face
// centroids, edge midpoints (each edge once per face).
Points samples(const Surface& s) {
  const std::vector<Eigen::Index> vertices = face_vertices(s);
  const auto count = static_cast<Eigen::Index>(vertices.size());
  Points P(count + 4 * s.F.rows(), 3);
  for (Eigen::Index k = 0; k < count; ++k) P.row(k) = s.V.row(vertices[static_cast<size_t>(k)]);
  Eigen::Index row = count;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = corner(s, f, 0), b = corner(s, f, 1), c = corner(s, f, 2);
    P.row(row++) = ((a + b + c) / 3.0).transpose();
    P.row(row++) = (0.5 * (a + b)).transpose();
    P.row(row++) = (0.5 * (b + c)).transpose();
    P.row(row++) = (0.5 * (c + a)).transpose();
  }
  return P;
}

// The largest and mean distance from the samples of `from` to the surface `to`.
void one_way(const Surface& from, const Surface& to, double& largest, double& mean) {
  const Points P = samples(from);
  const FaceBoxTree tree(to);
  const Eigen::Index n = P.rows();
  std::vector<double> d(static_cast<size_t>(n));
#pragma omp parallel for schedule(dynamic, 1024)
  for (Eigen::Index i = 0; i < n; ++i) d[static_cast<size_t>(i)] = tree.distance(P.row(i).transpose());
  largest = n > 0 ? *std::max_element(d.begin(), d.end()) : 0.0;
  double sum = 0.0;
  for (double x : d) sum += x;  // in order: the same bits on any thread count
  mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
}

// The largest distance from the samples P of one surface to the surface `to`, whose samples Q
// are their moved copies: the samples in order of how far they moved, searched in blocks until a
// block starts below the largest distance found. The largest of exact distances: the same value
// on any thread count.
double largest_one_way(const Points& P, const Points& Q, const Surface& to) {
  const Eigen::Index n = P.rows();
  using Moved = std::pair<double, Eigen::Index>;
  std::vector<Moved> moved(static_cast<size_t>(n));
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) moved[static_cast<size_t>(i)] = {(P.row(i) - Q.row(i)).norm(), i};
  auto further = [](const Moved& x, const Moved& y) { return x.first > y.first || (x.first == y.first && x.second < y.second); };
  const FaceBoxTree tree(to);
  constexpr Eigen::Index kBlock = 4096;
  double largest = 0.0;
  // In blocks, the samples that moved most first, until a block starts at no more than the largest
  // distance found.
  auto search = [&](const std::vector<Moved>& list, Eigen::Index count) {
    for (Eigen::Index start = 0; start < count && list[static_cast<size_t>(start)].first > largest; start += kBlock) {
      const Eigen::Index end = std::min(count, start + kBlock);
      std::vector<double> d(static_cast<size_t>(end - start), 0.0);
#pragma omp parallel for schedule(dynamic, 64)
      for (Eigen::Index k = start; k < end; ++k) {
        const auto& [bound, i] = list[static_cast<size_t>(k)];
        if (bound > largest) d[static_cast<size_t>(k - start)] = tree.distance(P.row(i).transpose());
      }
      for (double x : d) largest = std::max(largest, x);
    }
  };
  // Sorted in two rounds: the first block, then only the samples that moved more than its largest
  // distance (sorting all of them took as long as the searches).
  const Eigen::Index first = std::min(kBlock, n);
  std::partial_sort(moved.begin(), moved.begin() + first, moved.end(), further);
  search(moved, first);
  std::vector<Moved> rest;
  std::copy_if(moved.begin() + first, moved.end(), std::back_inserter(rest), [&](const Moved& m) { return m.first > largest; });
  std::sort(rest.begin(), rest.end(), further);
  search(rest, static_cast<Eigen::Index>(rest.size()));
  return largest;
}

}  // namespace

namespace {

Eigen::Vector3d closest_on_segment(const Eigen::Vector3d& q, const Eigen::Vector3d& p, const Eigen::Vector3d& r) {
  const Eigen::Vector3d e = r - p;
  const double l2 = e.squaredNorm();
  return l2 > 0.0 ? Eigen::Vector3d(p + std::clamp((q - p).dot(e) / l2, 0.0, 1.0) * e) : p;
}

}  // namespace

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const double scale = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  if (!(ab.cross(ac).squaredNorm() > 1e-24 * scale * scale)) {  // flat: the nearest of its three edges
    Eigen::Vector3d best = closest_on_segment(q, a, b);
    for (const Eigen::Vector3d& x : {closest_on_segment(q, b, c), closest_on_segment(q, c, a)})
      if ((x - q).squaredNorm() < (best - q).squaredNorm()) best = x;
    return best;
  }
  // Voronoi regions of the corners, the edges and the face (Ericson, Real-Time Collision Detection).
  const Eigen::Vector3d ap = q - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = q - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = q - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = va + vb + vc;
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

SurfaceDistance surface_distance(const Surface& a, const Surface& b) {
  check_surface(a);
  check_surface(b);
  SurfaceDistance d;
  if (a.F.rows() == 0 || b.F.rows() == 0) return d;
  one_way(a, b, d.a_to_b_max_mm, d.a_to_b_mean_mm);
  one_way(b, a, d.b_to_a_max_mm, d.b_to_a_mean_mm);
  d.hausdorff_mm = std::max(d.a_to_b_max_mm, d.b_to_a_max_mm);
  return d;
}

double hausdorff_of_moved(const Surface& a, const Surface& b) {
  check_surface(a);
  check_surface(b);
  if (a.V.rows() != b.V.rows() || a.F.rows() != b.F.rows() || a.F != b.F)
    throw std::invalid_argument("Hausdorff distance of a moved mesh: the two surfaces are not one mesh");
  if (a.F.rows() == 0) return 0.0;
  const Points P = samples(a), Q = samples(b);
  return std::max(largest_one_way(P, Q, b), largest_one_way(Q, P, a));
}

}  // namespace slim
