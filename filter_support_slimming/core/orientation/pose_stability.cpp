#include "core/orientation/pose_stability.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/print/rotation_to_up.h"

namespace slim {

namespace {

using Point2 = Eigen::Vector2d;

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain: the convex hull, counter-clockwise, without collinear corners.
std::vector<Point2> convex_hull_2d(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(), [](const Point2& a, const Point2& b) { return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y(); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Point2> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
    hull[k++] = p[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

Eigen::Vector3d centre_of_mass(const Surface& s) {
  const Eigen::Vector3d origin = s.V.colwise().mean().transpose();
  Eigen::Vector3d solid = Eigen::Vector3d::Zero(), shell = Eigen::Vector3d::Zero();
  double volume = 0.0, area = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)).transpose() - origin, b = s.V.row(s.F(f, 1)).transpose() - origin,
                          c = s.V.row(s.F(f, 2)).transpose() - origin;
    const double v = a.dot(b.cross(c)) / 6.0;  // the tet (origin, a, b, c)
    volume += v;
    solid += v * (a + b + c) / 4.0;
    const double w = 0.5 * (b - a).cross(c - a).norm();
    area += w;
    shell += w * (a + b + c) / 3.0;
  }
  const double size = bbox_diagonal(s.V);
  const bool closed = edge_topology(s).open_edges == 0;
  if (closed && std::abs(volume) > 1e-9 * size * size * size) return origin + solid / volume;
  return area > 0.0 ? Eigen::Vector3d(origin + shell / area) : origin;
}

PoseRest pose_rest(const Points& V, const Eigen::Vector3d& direction, double tolerance_mm,
                   const Eigen::Vector3d& centre) {
  const Eigen::Matrix3d up = rotation_to_up(direction);  // rows 0, 1: the plate's axes; row 2: d
  const Eigen::VectorXd height = V * up.row(2).transpose();
  const double plate = height.minCoeff();
  std::vector<Point2> touching;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (height(i) - plate <= tolerance_mm) touching.emplace_back(up.row(0).dot(V.row(i)), up.row(1).dot(V.row(i)));
  const std::vector<Point2> hull = convex_hull_2d(touching);
  PoseRest rest;
  if (hull.size() < 3) return rest;
  for (size_t k = 0; k < hull.size(); ++k) rest.footprint_mm2 += 0.5 * cross(hull[0], hull[k], hull[(k + 1) % hull.size()]);
  const Point2 c(up.row(0).dot(centre), up.row(1).dot(centre));
  const double margin = 1e-6 * bbox_diagonal(V);
  rest.stable = true;
  for (size_t k = 0; k < hull.size(); ++k) {
    const Point2 edge = hull[(k + 1) % hull.size()] - hull[k];
    if (cross(hull[k], hull[(k + 1) % hull.size()], c) < margin * edge.norm()) rest.stable = false;
  }
  return rest;
}

}  // namespace slim
