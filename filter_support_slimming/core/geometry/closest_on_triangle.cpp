#include "core/geometry/closest_on_triangle.h"

#include <algorithm>

#include <Eigen/Geometry>

namespace slim {

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

}  // namespace slim
