#include "core/rotation/min_rotation.h"

#include "core/rotation/near_repeats.h"
#include "core/rotation/nearest_feasible_point.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace slim {

namespace {

// Normals and d may come from float data: a little off unit length is accepted and renormalised.
constexpr double kUnitTolerance = 1e-6;

void check_inputs(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau,
                  const MinRotationOptions& options) {
  if (!(tau >= 0.0 && tau < 1.0))
    throw std::invalid_argument("min_rotation: tau = sin(alpha_max) must be in [0, 1), got " +
                                std::to_string(tau));
  if (!d.allFinite() || std::abs(d.norm() - 1.0) > kUnitTolerance)
    throw std::invalid_argument("min_rotation: the print direction d must be a finite unit vector");
  check_face_normals(normals, "min_rotation");
  if (!options.tie_break.allFinite())
    throw std::invalid_argument("min_rotation: tie_break must be finite");
  if (!(options.tie_tolerance >= 0.0) || !std::isfinite(options.tie_tolerance))
    throw std::invalid_argument("min_rotation: tie_tolerance must be a finite angle >= 0");
}

// Unit vector perpendicular to d: the caller's tie_break, else +X, else +Y, projected.
Eigen::Vector3d tie_direction(const Eigen::Vector3d& d, const Eigen::Vector3d& tie_break) {
  for (const Eigen::Vector3d& v : {tie_break, Eigen::Vector3d(Eigen::Vector3d::UnitX()),
                                   Eigen::Vector3d(Eigen::Vector3d::UnitY())}) {
    const Eigen::Vector3d w = v - v.dot(d) * d;
    const double length = w.norm();
    if (length > 1e-6 * v.norm()) return w / length;
  }
  return Eigen::Vector3d::UnitZ();  // unreachable for a unit d: X and Y cannot both be parallel to it
}

// The unit normals that constrain anything: zero columns (zero-area faces) dropped, and repeats of
// an earlier kept column too: columns closer than the feasibility tolerance are one constraint (a
// point feasible for one is feasible for the other within it, since |n·p - n'·p| <= |n - n'|).
// Thousands of them (the pieces of a flat face, a rigid feature on a CAD part, the faces of a
// subdivided triangle, whose normals differ in the last bits) would push the search onto its
// O(n²) path for nothing. The first of each stays where it was, so the order, and with it every
// tie, is the same as without the repeats.
Eigen::Matrix3Xd nonzero_unit_columns(const Eigen::Matrix3Xd& normals) {
  Eigen::Matrix3Xd unit(3, normals.cols());
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const double length = normals.col(i).norm();
    if (length > 0.0) unit.col(count++) = normals.col(i) / length;
  }
  const std::vector<Eigen::Index> first = near_repeats(unit.leftCols(count), kMinRotationFeasibilityTolerance);
  Eigen::Index kept = 0;
  for (Eigen::Index i = 0; i < count; ++i)
    if (first[static_cast<size_t>(i)] == i) unit.col(kept++) = unit.col(i);
  unit.conservativeResize(3, kept);
  return unit;
}

}  // namespace

void check_face_normals(const Eigen::Matrix3Xd& normals, const char* caller) {
  for (Eigen::Index i = 0; i < normals.cols(); ++i) {
    const double length = normals.col(i).norm();
    if (!std::isfinite(length))
      throw std::invalid_argument(std::string(caller) + ": normal " + std::to_string(i) + " is not finite");
    if (length != 0.0 && std::abs(length - 1.0) > kUnitTolerance)
      throw std::invalid_argument(std::string(caller) + ": normal " + std::to_string(i) + " has length " +
                                  std::to_string(length) +
                                  "; expected a unit vector (or exactly zero for a zero-area face)");
  }
}

GreatCircleRotation rotation_onto(const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                                  const Eigen::Vector3d& tangent) {
  // Work in the plane of d and the unit tangent t at d pointing towards c: c = cos(a) d + sin(a) t,
  // and R maps d -> cos(a) d - sin(a) t, t -> sin(a) d + cos(a) t, fixing t × d. Built from t
  // rather than from c × d, R c = d holds to rounding even when c is close to -d.
  const double along = c.dot(d);
  const Eigen::Vector3d off = c - along * d;
  const double off_length = off.norm();
  const Eigen::Vector3d t = off_length > kTinyTangent ? Eigen::Vector3d(off / off_length) : tangent;
  GreatCircleRotation g;
  if (off_length <= kTinyTangent && along > 0.0) {  // c is d, to rounding: exactly no rotation
    g.angle = 0.0;
    g.rotation.setIdentity();
    g.axis = tangent.cross(d).normalized();
    return g;
  }
  g.angle = std::atan2(off_length, along);
  const double cos_a = std::cos(g.angle), sin_a = std::sin(g.angle);
  g.rotation = Eigen::Matrix3d::Identity() + (cos_a - 1.0) * (d * d.transpose() + t * t.transpose()) +
               sin_a * (d * t.transpose() - t * d.transpose());
  g.axis = t.cross(d).normalized();
  return g;
}

MinRotation min_rotation(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau) {
  return min_rotation(normals, d, tau, MinRotationOptions{});
}

MinRotation min_rotation(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d_in, double tau,
                         const MinRotationOptions& options) {
  check_inputs(normals, d_in, tau, options);
  const Eigen::Vector3d d = d_in.normalized();
  const Eigen::Vector3d tie = tie_direction(d, options.tie_break);
  const Eigen::Matrix3Xd unit_normals = nonzero_unit_columns(normals);

  MinRotation result;
  Eigen::Vector3d closest;
  result.feasible = nearest_feasible_point(unit_normals, d, tau, tie, options.tie_tolerance, closest);
  if (!result.feasible) closest = d;  // nothing to rotate towards: stay put
  const GreatCircleRotation g = rotation_onto(closest, d, tie);
  result.closest = closest;
  result.angle = g.angle;
  result.axis = g.axis;
  result.rotation = g.rotation;
  return result;
}

}  // namespace slim
