// The point of the feasible region on the sphere nearest to d: the heart of the minimal rotation
// (min_rotation.h says why that point is the answer and what the region looks like).
//
//   bool found = nearest_feasible_point(normals, d, tau, tie, tie_tolerance, closest)
//
// Inputs
//   normals        3 by m unit normals, none zero and no two closer than
//                  kMinRotationFeasibilityTolerance (min_rotation drops those first).
//   d              unit print direction.
//   tau            sin(alpha_max), in [0, 1).
//   tie            unit vector perpendicular to d: among points within tie_tolerance (radians) of
//                  the smallest angle, the one whose direction away from d best matches it wins.
// Output
//   false when H = { p : n_i·p >= -tau - kMinRotationFeasibilityTolerance for all i } is empty;
//   else true, and closest is the unit point of H nearest to d (d itself when d is in H).
//
// How: every point that can be the nearest is enumerated (d, each boundary circle's point nearest
// to d, crossings of two circles), nearest first, each checked against every constraint.
//  * Fewer than 24 normals: all pairs of circles, screened by arithmetic alone against the best
//    point so far. O(m²) in practice.
//  * More: first an active set. H grows when constraints are left out, so the answer on a subset
//    is at least as near as the whole set's, and is the whole set's when it violates none of them;
//    and if a subset leaves no region, the whole set leaves none. Start from the 16 constraints
//    most violated at d, solve on them, add the 8 the answer violates most, repeat: each round is
//    one O(m) check, and two constraints fix an answer. A patch of one surface (normals within a
//    few tens of degrees) is settled in a round or two. After 3 rounds undecided (a wide patch,
//    normals all round the lower hemisphere), the hull:
//  * only the pairs that are edges of the normals' convex hull can cross at a feasible point
//    (nearest_feasible_point.cpp says why): hull O(m log m) expected, O(m) edges;
//  * and where that hull is too nearly degenerate to trust (normals a few ulps apart, four nearly
//    co-circular ones: a scan's tet, a tight cluster of a hundred or more), the active set again,
//    without a limit on rounds. (Before: all O(m²) pairs.)
// Timings (bench/min_rotation_bench.cpp): see min_rotation.h.
#pragma once

#include <Eigen/Core>

namespace slim {

// Below this length a tangent direction at d is rounding noise and the tie-break direction is used
// (here and in min_rotation's rotation_onto).
inline constexpr double kTinyTangent = 1e-14;

bool nearest_feasible_point(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau,
                            const Eigen::Vector3d& tie, double tie_tolerance, Eigen::Vector3d& closest);

}  // namespace slim
