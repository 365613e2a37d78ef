#include "support/min_rotation_reference.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/rotation/min_rotation.h"

namespace slim::test {

namespace {

using Real = long double;
using Vec = Eigen::Matrix<Real, 3, 1>;

struct Problem {
  std::vector<Vec> n;  // unit, zero normals dropped
  Vec d;
  Real tau;

  bool feasible(const Vec& p) const {
    for (const Vec& ni : n)
      if (ni.dot(p) + tau < -static_cast<Real>(kMinRotationFeasibilityTolerance)) return false;
    return true;
  }
};

Vec any_perpendicular(const Vec& v) {
  const Vec a = std::abs(v.x()) < 0.9L ? Vec(1, 0, 0) : Vec(0, 1, 0);
  return (a - a.dot(v) * v).normalized();
}

}  // namespace

ReferenceMinRotation reference_min_rotation(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau) {
  Problem problem;
  problem.d = d.cast<Real>().normalized();
  problem.tau = tau;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const Vec v = normals.col(i).cast<Real>();
    if (v.norm() > 0) problem.n.push_back(v.normalized());
  }

  ReferenceMinRotation best;
  best.closest = d;
  Real best_cos = -2;  // cos of the best angle so far
  auto consider = [&](Vec p) {
    p.normalize();
    const Real c = problem.d.dot(p);
    if (c <= best_cos || !problem.feasible(p)) return;
    best_cos = c;
    best.feasible = true;
    best.closest = p.cast<double>();
    best.angle = std::atan2(p.cross(problem.d).norm(), c);
  };

  consider(problem.d);
  const Real radius = std::sqrt(1 - problem.tau * problem.tau);
  for (const Vec& ni : problem.n) {
    Vec towards_d = problem.d - problem.d.dot(ni) * ni;  // direction of the nearest circle point
    towards_d = towards_d.norm() > 0 ? Vec(towards_d.normalized()) : any_perpendicular(ni);
    consider(-problem.tau * ni + radius * towards_d);
  }
  for (size_t i = 0; i < problem.n.size(); ++i) {
    for (size_t j = i + 1; j < problem.n.size(); ++j) {
      const Vec &a = problem.n[i], &b = problem.n[j];
      // The planes' line: p0 + s u, p0 = x (a + b) by symmetry; a·p0 = x (1 + a·b) = -tau, where
      // 1 + a·b = |a + b|² / 2 is taken from the sum for accuracy; u ∥ a × b, computed as
      // a × (b ∓ a), which is the same vector but keeps its precision when b is close to ±a.
      const Real one_plus_g = (a + b).squaredNorm() / 2;
      const Vec axis = a.dot(b) >= 0 ? Vec(a.cross(b - a)) : Vec(a.cross(b + a));
      if (axis.norm() == 0) continue;  // same or opposite circles: covered by the circle points
      const Vec p0 = problem.tau == 0 ? Vec::Zero() : Vec(-problem.tau / one_plus_g * (a + b));
      const Real h2 = 1 - p0.squaredNorm();
      if (h2 < 0) continue;  // the circles do not meet
      const Vec u = axis.normalized();
      consider(p0 + std::sqrt(h2) * u);
      consider(p0 - std::sqrt(h2) * u);
    }
  }
  return best;
}

Eigen::Vector3d random_in_cap(std::mt19937& rng, const Eigen::Vector3d& axis, double max_angle) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double z = 1.0 - unit(rng) * (1.0 - std::cos(max_angle));  // area-uniform on the cap
  const double phi = 2.0 * M_PI * unit(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Vector3d helper = std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = a.cross(helper).normalized(), e2 = a.cross(e1);
  return (z * a + r * std::cos(phi) * e1 + r * std::sin(phi) * e2).normalized();
}

Eigen::Vector3d random_unit_vector(std::mt19937& rng) { return random_in_cap(rng, Eigen::Vector3d::UnitZ(), M_PI); }

Eigen::Matrix3Xd random_normals_in_cap(std::mt19937& rng, int n, const Eigen::Vector3d& axis, double max_angle) {
  Eigen::Matrix3Xd normals(3, n);
  for (int i = 0; i < n; ++i) normals.col(i) = random_in_cap(rng, axis, max_angle);
  return normals;
}

double sampled_min_angle(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau, int samples) {
  double best = std::numeric_limits<double>::infinity();
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < samples; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / samples;
    const double r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d p(r * std::cos(golden * k), r * std::sin(golden * k), z);
    bool safe = true;
    for (Eigen::Index i = 0; i < normals.cols() && safe; ++i) safe = normals.col(i).dot(p) + tau >= 0.0;
    if (!safe) continue;
    best = std::min(best, std::acos(std::clamp(p.dot(d), -1.0, 1.0)));
  }
  return best;
}

}  // namespace slim::test
