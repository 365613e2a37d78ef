// Where a surface intersects itself: two faces that meet where they share no edge, the input
// that makes TetGen 1.5 crash (tetgen_domain.h refuses it first).
//
//   bool first_self_intersection(surface, f, g)
//
// In:  a surface (#V by 3, #F by 3 indices into V, all checked: checked_surface.h).
// Out: true, with f < g the lexicographically smallest pair of faces that meet improperly; false
//      when there is none. Improperly: faces with no common vertex that touch anywhere; faces that
//      share one vertex and meet anywhere else; faces that share an edge and fold onto each other
//      (coplanar, on the same side); the same triangle twice.
// The predicates are plain double orientation tests: exact zeros come from exactly coplanar data,
// which is what CAD meshes have. Candidate pairs come from a uniform grid of face boxes (about one
// cell per face, each pair tested once, in the cell holding the low corner of the boxes'
// overlap), so the check stays near-linear; the answer does not depend on the thread count.
#pragma once

#include "core/geometry/surface.h"

namespace slim {

bool first_self_intersection(const Surface& surface, int& f, int& g);

}  // namespace slim
