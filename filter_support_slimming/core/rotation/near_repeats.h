// Which unit vectors repeat an earlier one: the columns closer than a tolerance to a column before
// them that is kept itself.
//
//   std::vector<Eigen::Index> kept = near_repeats(unit, tolerance);
//
// Inputs
//   unit       3 by n vectors (unit normals, in practice), any order.
//   tolerance  >= 0: columns i < j with |u_i - u_j| <= tolerance are one (0: exact repeats only).
// Output: n indices; kept[j] = j when column j is kept, else the kept column i < j within the
//   tolerance that it repeats (the first such in column order). The first of each group is kept,
//   so an order-dependent caller (ties) sees the same kept columns in the same order as without
//   the repeats.
// Why: the faces of a subdivided triangle, the pieces of a flat face, a rigid feature on a CAD
// part give thousands of normals that differ in their last bits; for the minimal rotation they
// are one constraint (min_rotation.h), and thousands of them cost O(n²).
// Cost: O(n) expected: the kept columns in a grid of cells as wide as the tolerance, each column
// compared with the kept ones of its own and the 26 neighbouring cells (a plain pass below 32).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace slim {

std::vector<Eigen::Index> near_repeats(const Eigen::Matrix3Xd& unit, double tolerance);

}  // namespace slim
