#include "core/surface.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slim {

namespace {
Eigen::Vector3d face_cross(const Surface& s, Eigen::Index f) {
  const Eigen::Vector3d a = s.V.row(s.F(f, 0)).transpose();
  const Eigen::Vector3d b = s.V.row(s.F(f, 1)).transpose();
  const Eigen::Vector3d c = s.V.row(s.F(f, 2)).transpose();
  return (b - a).cross(c - a);
}
}  // namespace

Points face_normals(const Surface& s) {
  Points n(s.F.rows(), 3);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d c = face_cross(s, f);
    const double len = c.norm();
    // A face whose area underflows has no direction; zero keeps it out of every constraint.
    if (len > 0.0 && std::isfinite(len))
      n.row(f) = (c / len).transpose();
    else
      n.row(f).setZero();
  }
  return n;
}

Eigen::VectorXd face_areas(const Surface& s) {
  Eigen::VectorXd a(s.F.rows());
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) a(f) = 0.5 * face_cross(s, f).norm();
  return a;
}

void check_surface(const Surface& s) {
  if (!s.V.allFinite()) throw std::invalid_argument("the mesh has a vertex with a NaN or infinite coordinate");
  const Eigen::Index nv = s.V.rows();
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (s.F(f, k) < 0 || s.F(f, k) >= nv)
        throw std::invalid_argument("face " + std::to_string(f) + " refers to vertex " + std::to_string(s.F(f, k)) +
                                    ", but the mesh has " + std::to_string(nv) + " vertices");
}

double signed_volume(const Surface& s) {
  double vol = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)).transpose();
    const Eigen::Vector3d b = s.V.row(s.F(f, 1)).transpose();
    const Eigen::Vector3d c = s.V.row(s.F(f, 2)).transpose();
    vol += a.dot(b.cross(c));
  }
  return vol / 6.0;
}

}  // namespace slim
