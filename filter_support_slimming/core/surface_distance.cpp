#include "core/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/uniform_grid.h"

namespace slim {

namespace {

Eigen::Vector3d corner(const Surface& s, Eigen::Index f, int k) { return s.V.row(s.F(f, k)).transpose(); }

// The samples of a surface: vertices, face centroids, edge midpoints (each edge once per face).
Points samples(const Surface& s) {
  Points P(s.V.rows() + 4 * s.F.rows(), 3);
  P.topRows(s.V.rows()) = s.V;
  Eigen::Index row = s.V.rows();
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = corner(s, f, 0), b = corner(s, f, 1), c = corner(s, f, 2);
    P.row(row++) = ((a + b + c) / 3.0).transpose();
    P.row(row++) = (0.5 * (a + b)).transpose();
    P.row(row++) = (0.5 * (b + c)).transpose();
    P.row(row++) = (0.5 * (c + a)).transpose();
  }
  return P;
}

// The faces of s in a uniform grid of about one cell per face.
UniformGrid face_grid(const Surface& s) {
  const Eigen::Vector3d lo = s.V.colwise().minCoeff().transpose(), hi = s.V.colwise().maxCoeff().transpose();
  const double diag = (hi - lo).norm();
  const Eigen::Vector3d extent = (hi - lo) + Eigen::Vector3d::Constant(1e-9 * diag + 1e-300);
  const double side = std::cbrt(extent.prod() / std::max<double>(1.0, static_cast<double>(s.F.rows())));
  Eigen::Vector3i dims;
  for (int a = 0; a < 3; ++a) dims(a) = std::clamp(static_cast<int>(std::ceil(extent(a) / std::max(side, 1e-300))), 1, 256);
  UniformGrid grid(lo, extent.cwiseQuotient(dims.cast<double>()), dims);
  grid.fill(static_cast<int>(s.F.rows()), [&](int f, Eigen::Vector3d& a, Eigen::Vector3d& b) {
    a = corner(s, f, 0).cwiseMin(corner(s, f, 1)).cwiseMin(corner(s, f, 2));
    b = corner(s, f, 0).cwiseMax(corner(s, f, 1)).cwiseMax(corner(s, f, 2));
  });
  return grid;
}

// The distance from q to the surface `to` whose faces fill `grid`.
double distance_to(const Eigen::Vector3d& q, const Surface& to, const UniformGrid& grid) {
  double best = HUGE_VAL;
  grid.nearest(q, [&](int f) { return (closest_on_triangle(q, corner(to, f, 0), corner(to, f, 1), corner(to, f, 2)) - q).norm(); },
               best);
  return best;
}

// The largest and mean distance from the samples of `from` to the surface `to`.
void one_way(const Surface& from, const Surface& to, double& largest, double& mean) {
  const Points P = samples(from);
  const UniformGrid grid = face_grid(to);
  const Eigen::Index n = P.rows();
  std::vector<double> d(static_cast<size_t>(n));
#pragma omp parallel for schedule(dynamic, 1024)
  for (Eigen::Index i = 0; i < n; ++i) d[static_cast<size_t>(i)] = distance_to(P.row(i).transpose(), to, grid);
  largest = n > 0 ? *std::max_element(d.begin(), d.end()) : 0.0;
  double sum = 0.0;
  for (double x : d) sum += x;  // in order: the same bits on any thread count
  mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
}

// The largest distance from the samples P of one surface to the surface `to`, whose samples Q
// are their moved copies: the samples in order of how far they moved, searched in blocks until a
// block starts below the largest distance found (a sample with a face of its own grid cell that
// near is skipped). The largest of exact distances: the same value on any thread count.
double largest_one_way(const Points& P, const Points& Q, const Surface& to) {
  const Eigen::Index n = P.rows();
  std::vector<std::pair<double, Eigen::Index>> moved(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) moved[static_cast<size_t>(i)] = {(P.row(i) - Q.row(i)).norm(), i};
  std::sort(moved.begin(), moved.end(), [](const auto& x, const auto& y) { return x.first > y.first || (x.first == y.first && x.second < y.second); });
  const UniformGrid grid = face_grid(to);
  constexpr Eigen::Index kBlock = 4096;
  double largest = 0.0;
  for (Eigen::Index start = 0; start < n && moved[static_cast<size_t>(start)].first > largest; start += kBlock) {
    const Eigen::Index end = std::min(n, start + kBlock);
    std::vector<double> d(static_cast<size_t>(end - start), 0.0);
#pragma omp parallel for schedule(dynamic, 64)
    for (Eigen::Index k = start; k < end; ++k) {
      const auto& [bound, i] = moved[static_cast<size_t>(k)];
      if (!(bound > largest)) continue;
      const Eigen::Vector3d p = P.row(i).transpose();
      // A face of the sample's own cell within the largest distance found already: the sample
      // cannot raise it, and the full search (its shells of cells) is spared. Most samples of a
      // slimmed part slid along the surface further than the part moved off it.
      bool near = false;
      for (int f : grid.items(grid.index(grid.cell_of(p))))
        if ((closest_on_triangle(p, corner(to, f, 0), corner(to, f, 1), corner(to, f, 2)) - p).norm() <= largest) {
          near = true;
          break;
        }
      if (!near) d[static_cast<size_t>(k - start)] = distance_to(p, to, grid);
    }
    for (double x : d) largest = std::max(largest, x);
  }
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
