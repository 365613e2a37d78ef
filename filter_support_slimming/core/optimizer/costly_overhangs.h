// Which overhangs the optimizer turns: the ones whose support costs most. A face's cost is the
// prism of support under it, down to what the column would stand on (face_columns.h):
//   area (mm²) x its footprint -(n·d) x its column height (mm)  (mm³, overhang.h: face_shadow).
// The risky faces are ranked by that cost and the costliest are kept until they carry `share` of
// the total: the overhangs high above the plate first, those just above the plate or just above
// the part below last. The rest are left alone: no turns are asked for them (local_step.h), no
// free region is grown around them (support_region.h) and their tets are not boosted. A short
// column costs the slicer little, and turning its faces spends the shape's limits (creases, the
// top's rise) that the tall ones need.
//
//   std::vector<bool> costly = costly_overhangs(input, before, d, share);
//
// Inputs
//   input   the surface, #V by 3 mm, #F by 3.
//   before  the input's overhang report (overhang.h): its risky faces.
//   d       the unit print direction.
//   share   in (0, 1]: the share of the total cost the kept faces carry; 1 keeps every risky face.
// Output: #F flags, a subset of before.risky. Ties in cost go to the lower face index; a face with
//   no cost (no area, or resting on what is below) is kept only at share 1.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"
#include "core/print/overhang.h"

namespace slim {

std::vector<bool> costly_overhangs(const Surface& input, const OverhangReport& before, const Eigen::Vector3d& d,
                                   double share);

}  // namespace slim
