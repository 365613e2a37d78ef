// The smallest rotation about a given axis that makes a patch of faces self-supporting.
//
//   MinRotation min_rotation_about_axis(normals, d, tau, axis)
//
// min_rotation.h finds the smallest rotation about any axis. The coherent method sometimes wants
// the turn in a chosen sense instead: a nearly flat overhang towards the nearest edge of its
// region (slimming.cpp), which can cost a few degrees more than the minimal turn but lets the
// strips along opposite edges meet instead of folding the whole overhang one way.
//
// Inputs
//   normals  3 by n face normals, unit length (|‖n‖ - 1| <= 1e-6) or exactly zero (ignored).
//   d        unit print direction.
//   tau      sin(alpha_max), in [0, 1).
//   axis     unit rotation axis; the turn is right-handed about it, by an angle in [0, pi].
// Output (MinRotation, as in min_rotation.h)
//   feasible  some angle in [0, pi] makes every face safe: (R n_i)·d >= -tau (within
//             kMinRotationFeasibilityTolerance) for all i.
//   angle     the smallest such angle (radians); axis = the given axis; rotation R; closest = Rᵀd.
// When no angle in [0, pi] works: feasible = false, angle = 0, rotation = identity, closest = d.
// Throws std::invalid_argument for bad normals, a non-unit or non-finite d or axis, or tau
// outside [0, 1).
//
// Exactness. About a fixed axis a face's test is a sinusoid in the angle,
//   (R(θ) n)·d + tau = P + Q cos θ + S sin θ,
// so each face is safe on one arc of angles (or on all, or on none). The smallest safe angle is 0
// or the start of some face's arc: every arc end in [0, pi] is a candidate, checked against all
// faces in ascending order. O(n²) for n faces; n is a tet's face pieces, a few dozen at most.
#pragma once

#include <Eigen/Core>

#include "core/rotation/min_rotation.h"

namespace slim {

MinRotation min_rotation_about_axis(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau,
                                    const Eigen::Vector3d& axis);

}  // namespace slim
