// Independent checks for slim::min_rotation: the plain O(n³) enumeration in long double, and
// dense sampling of the sphere.
//
// reference_min_rotation: inputs as min_rotation (3 by n normals, zero columns ignored; unit d;
// tau in [0, 1)). Every point that can be the nearest feasible one is tried against every
// constraint: d, the point of each boundary circle n_i·p = -tau nearest to d, and both crossings of
// every two circles. A point counts as feasible with the same tolerance as the solver,
// n_i·p + tau >= -kMinRotationFeasibilityTolerance. Exact up to long double rounding; slow.
//
// sampled_min_angle: the smallest angle (radians) from d over the feasible points of a Fibonacci
// lattice of `samples` points on the sphere, or +infinity when none is feasible. Only an upper bound
// of the true minimum, and blind to regions thinner than the lattice spacing.
#pragma once

#include <random>

#include <Eigen/Core>

namespace slim::test {

struct ReferenceMinRotation {
  bool feasible = false;
  long double angle = 0;    // radians
  Eigen::Vector3d closest;  // the nearest feasible point found (d when infeasible)
};

ReferenceMinRotation reference_min_rotation(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau);

double sampled_min_angle(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau, int samples);

// Random unit normals for the tests and benchmarks; the same rng state gives the same vectors.
// Area-uniform on the cap of half-angle max_angle radians about axis (pi: the whole sphere).
Eigen::Vector3d random_in_cap(std::mt19937& rng, const Eigen::Vector3d& axis, double max_angle);
Eigen::Vector3d random_unit_vector(std::mt19937& rng);
Eigen::Matrix3Xd random_normals_in_cap(std::mt19937& rng, int n, const Eigen::Vector3d& axis, double max_angle);

}  // namespace slim::test
