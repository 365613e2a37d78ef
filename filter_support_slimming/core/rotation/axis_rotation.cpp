#include "core/rotation/axis_rotation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace slim {

MinRotation min_rotation_about_axis(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d_in, double tau,
                                    const Eigen::Vector3d& axis_in) {
  if (!(tau >= 0.0 && tau < 1.0)) throw std::invalid_argument("min_rotation_about_axis: tau must be in [0, 1)");
  for (const Eigen::Vector3d* v : {&d_in, &axis_in})
    if (!v->allFinite() || std::abs(v->norm() - 1.0) > 1e-6)
      throw std::invalid_argument("min_rotation_about_axis: d and the axis must be finite unit vectors");
  check_face_normals(normals, "min_rotation_about_axis");
  const Eigen::Vector3d d = d_in.normalized(), a = axis_in.normalized();

  // Face i at angle θ: P + Q cos θ + S sin θ, from n(θ) = (n·a)a + cos θ (n - (n·a)a) + sin θ a×n.
  struct Sinusoid {
    double p, q, s;
    double at(double theta) const { return p + q * std::cos(theta) + s * std::sin(theta); }
  };
  std::vector<Sinusoid> faces;
  std::vector<double> candidates{0.0};
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    if (normals.col(i).squaredNorm() == 0.0) continue;
    const Eigen::Vector3d n = normals.col(i).normalized();
    const double along = n.dot(a) * a.dot(d);
    const Sinusoid f{along + tau, n.dot(d) - along, a.cross(n).dot(d)};
    faces.push_back(f);
    // Safe where cos(θ - φ) >= -p / amplitude: the arc φ ± acos(-p / amplitude).
    const double amplitude = std::hypot(f.q, f.s);
    if (!(amplitude > 0.0) || std::abs(f.p) >= amplitude) continue;  // safe at every angle, or at none
    const double phi = std::atan2(f.s, f.q), half = std::acos(-f.p / amplitude);
    for (double end : {phi - half, phi + half}) {
      const double wrapped = end - 2.0 * M_PI * std::floor(end / (2.0 * M_PI));  // [0, 2π)
      if (wrapped <= M_PI) candidates.push_back(wrapped);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  MinRotation r;
  r.closest = d;
  r.axis = a;
  for (double theta : candidates) {
    bool safe = true;
    for (const Sinusoid& f : faces) safe = safe && f.at(theta) >= -kMinRotationFeasibilityTolerance;
    if (!safe) continue;
    r.feasible = true;
    r.angle = theta;
    r.rotation = Eigen::AngleAxisd(theta, a).toRotationMatrix();
    r.closest = r.rotation.transpose() * d;
    break;
  }
  return r;
}

}  // namespace slim
