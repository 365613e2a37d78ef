// The exact minimal rotation of one patch of faces on the Gauss sphere (paper §III-A/B).
//
//   MinRotation min_rotation(normals, d, tau [, options])
//
// Inputs
//   normals  3 by n face normals, unit length (|‖n‖ - 1| <= 1e-6, renormalised here). An exact
//            zero column is a zero-area face: it has no direction, so it is ignored (weight 0).
//   d        unit print direction (|‖d‖ - 1| <= 1e-6, renormalised here).
//   tau      sin(alpha_max), in [0, 1): alpha_max is the self-supporting angle from the vertical.
//   options  tie-break for the equally-near points of a face pointing straight down; see below.
// Output (MinRotation)
//   feasible  some rotation makes every face safe: (R n_i)·d >= -tau for all i.
//   closest   unit point c of the feasible region on the sphere geodesically nearest to d.
//   angle     radians in [0, pi], the geodesic distance from c to d, which is the rotation angle.
//   axis      unit rotation axis, c × d normalised.
//   rotation  3 by 3 proper rotation R, R c = d; apply it to the patch (R n_i) to make it safe.
// When no rotation exists: feasible = false, rotation = identity, angle = 0, closest = d. When the
// angle is 0 the axis is meaningless but still a deterministic unit vector perpendicular to d.
// Throws std::invalid_argument for a non-unit or non-finite normal, a non-unit or non-finite d,
// tau outside [0, 1) or NaN, or a non-finite tie_break / negative tie_tolerance. Never returns NaN.
//
// Why the answer is c and R turns c onto d: the constraint (R n_i)·d >= -tau is n_i·(Rᵀd) >= -tau,
// so Rᵀd must lie in the feasible region H = { p on the sphere : n_i·p >= -tau for all i }, and
// the smallest rotation takes the point of H nearest to d onto d, about c × d. (The paper writes
// the axis as d × c, which with a right-handed angle gives the inverse rotation.)
//
// Exactness. H is the sphere minus n open caps of equal angular radius acos(tau) centred on -n_i.
// For tau > 0 it is not convex, so the paper's "nearest corner and its two edges" can miss the
// answer; and H can have no corner at all (one face, or circles that never cross). The nearest
// point of H is always one of: d itself; the point of a boundary circle n_i·p = -tau nearest to d;
// a crossing of two boundary circles. All of them are enumerated, so zero-width regions (an
// antipodal pair at tau = 0 leaves one great circle) are found too.
//
// Feasibility tolerance: a point is feasible when n_i·p + tau >= -kMinRotationFeasibilityTolerance
// for every i. It absorbs rounding in the computed crossings and lets boundary-thin regions count.
//
// Complexity (n normals, after dropping zero ones and near repeats; nearest_feasible_point.h):
//  * The n boundary-circle points: O(n log n), feasibility checked nearest first with early exit.
//  * Crossings, n < 24: all O(n²) pairs, screened by arithmetic against the best point so far.
//  * Crossings, n >= 24: an active set (a few constraints at a time, each answer checked against
//    all, O(n) a round) for up to 3 rounds; then only the circle pairs that are edges of the convex
//    hull of the normals, O(n log n); where that hull is numerically degenerate (normals a few ulps
//    apart, four nearly co-circular normals: a scan's tight cluster), the active set to the end.
// Timings: bench/min_rotation_bench.cpp, docs/speed.md.
// Memory O(n).
#pragma once

#include <Eigen/Core>

namespace slim {

// n_i·p + tau >= -this counts as safe; the reference tests use the same value.
inline constexpr double kMinRotationFeasibilityTolerance = 1e-12;

struct MinRotationOptions {
  // A face pointing straight down (n = -d) makes every point of the circle p·d = tau equally near.
  // Among points whose angle is within tie_tolerance of the minimum, the one whose direction away
  // from d (its tangent at d) best matches tie_break wins. Only tie_break's component
  // perpendicular to d matters; if that is (nearly) zero, +X projected perpendicular to d is used,
  // and if d is (nearly) ±X, +Y projected. Callers pass a direction from geometry (e.g. away from
  // the part's axis) so that neighbouring patches bend the same way (paper Fig. 8).
  Eigen::Vector3d tie_break = Eigen::Vector3d::UnitX();  // default: +X, projected perpendicular to d
  double tie_tolerance = 1e-9;                           // radians; 0 = only exact ties
};

struct MinRotation {
  bool feasible = false;
  Eigen::Vector3d closest = Eigen::Vector3d::UnitZ();  // unit; Rᵀd
  double angle = 0.0;                                  // radians
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();     // unit, perpendicular to d when angle = 0
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

MinRotation min_rotation(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau);
MinRotation min_rotation(const Eigen::Matrix3Xd& normals, const Eigen::Vector3d& d, double tau,
                         const MinRotationOptions& options);

// The rotation that turns the unit point c onto the unit point d along their great circle, with
// its axis; when c = ±d (no unique great circle) it turns about the axis tangent × d instead,
// where tangent is a unit vector perpendicular to d. Exposed for the proxy and local steps.
struct GreatCircleRotation {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d axis;  // unit
  double angle;          // radians in [0, pi]
};
GreatCircleRotation rotation_onto(const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                                  const Eigen::Vector3d& tangent);

// Throws std::invalid_argument, naming `caller`, unless every column of the 3 by n `normals` is
// finite and either unit (|‖n‖ - 1| <= 1e-6) or exactly zero (a zero-area face).
void check_face_normals(const Eigen::Matrix3Xd& normals, const char* caller);

}  // namespace slim
