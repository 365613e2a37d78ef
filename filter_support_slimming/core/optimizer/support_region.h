// What the support does not need stays where it was: a spring from each domain vertex to its rest
// position, zero near the overhangs that cost support and full far from them. The global step
// factors the springs with its matrix (arap.h: anchors), so the deformation stays local: the part
// keeps its size and proportions instead of growing taller and thinner to carry the turns of its
// underside.
//
//   Eigen::VectorXd a = region_anchors(input, risky, domain, diagonal_mm, options);
//
// Inputs
//   input        the surface, #V by 3 mm, #F by 3.
//   risky        #F, the faces that need support at the start (overhang.h): the seeds.
//   domain       the tet domain, #DV by 3 mm, #DT by 4, positive tets.
//   diagonal_mm  the input's bounding-box diagonal (> 0): the radii are shares of it.
//   options      RegionOptions (slimming_options.h): the free radius, the ramp, the stiffness.
// Output: #DV spring weights (mm^3), a_v = stiffness * vol_v * ramp(dist_v), where vol_v is a
//   quarter of the rest volume of the tets at v and dist_v the distance from v to the nearest
//   risky face; ramp is 0 up to free_radius, rises smoothly (a cubic smoothstep) over ramp_width
//   and is 1 beyond. The weight is per volume so that it does not depend on the resolution: a
//   region of size D stretched by a strain e costs the springs about stiffness * D^5 e^2 and the
//   tets D^3 h^2 e^2 (h the cell size), so even a small stiffness holds a far region.
//   No risky face: every vertex is anchored. Empty options (stiffness 0): an empty vector.
// Cost: one box-tree query per domain vertex (face_box_tree.h), parallel; deterministic.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"
#include "core/optimizer/slimming_options.h"

namespace slim {

Eigen::VectorXd region_anchors(const Surface& input, const std::vector<bool>& risky, const TetMesh& domain,
                               double diagonal_mm, const RegionOptions& options);

// The distance (mm) from each domain vertex to the nearest of `faces` of `input` (#F flags);
// +infinity for every vertex when no face is flagged.
Eigen::VectorXd distance_to_faces(const Surface& input, const std::vector<bool>& faces, const Points& points);

}  // namespace slim
