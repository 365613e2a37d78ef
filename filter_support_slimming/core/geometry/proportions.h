// What a deformation did to the part's size and proportions, result against input: what a print
// engineer checks before the volume and the creases (does the part still fit, is a figure still
// itself, did a face fold over).
//
//   Proportions p = proportions(input, result_V, d);
//
// Inputs
//   input     #V by 3 positions (mm) and #F by 3 faces: the shape before (checked, surface.h).
//   result_V  #V by 3 positions (mm) of the same vertices after the deformation (same order).
//   d         the print direction (unit): the part's height is its extent along d.
// Outputs (Proportions)
//   extent_change_pct   per axis x, y, z: 100 (extent_result / extent_input - 1), the extents of
//                       the vertices' bounding boxes; 0 along an axis where the input has none.
//   height_change_pct   the same along d.
//   folded_faces        faces whose normal turned by more than 90 degrees (n_input · n_result < 0;
//                       faces of zero area in either shape are left out): a fold, which a slicer
//                       reads as a sliver or a self-intersection.
//   affine_departure_pct  how far the best-fit affine map from the input's vertices to the
//                       result's departs from a rigid motion: 100 max_i |sigma_i - 1|, sigma the
//                       singular values of its linear part. The map fits the displacements
//                       (least squares over the vertices, each alike, about their centroid) with
//                       the least-norm solution, so a direction in which a flat input has no
//                       extent neither stretches nor squashes. A global stretch or squash of 3%
//                       reads 3; a local bend, little.
// Cost: O(#V + #F). Throws std::invalid_argument when result_V is not #V by 3 or not finite.
#pragma once

#include <Eigen/Core>

#include "core/geometry/surface.h"

namespace slim {

struct Proportions {
  Eigen::Vector3d extent_change_pct = Eigen::Vector3d::Zero();
  double height_change_pct = 0.0;
  long folded_faces = 0;
  double affine_departure_pct = 0.0;
};

Proportions proportions(const Surface& input, const Points& result_V, const Eigen::Vector3d& d);

// The least-norm solve of the affine fit's normal equations G B = R (G = Xc^T Xc of the centred
// input, 3 by 3): a direction in which the input's extent is below 1e-9 of its largest is left
// out. Shared with the optimizer's stretch constraints (rigid_proportions.h), so both read one map.
Eigen::Matrix3d affine_fit_solve(const Eigen::Matrix3d& G, const Eigen::Matrix3d& R);

}  // namespace slim
