// How neighbouring tets turn together: the coherent method's parts of the local step
// (CoherenceOptions in slimming.h). The paper rotates every tet on its own, so neighbours bend
// opposite ways (its Fig. 8) and a region turns as a skin, not as a body.
//
//   TieDirections tie = tie_directions(input, domain, pieces, rest_normals, risky, d, diag, coherence);
//   auto neighbours = tet_neighbours(domain.T, domain.V.rows(), holds_faces);
//   blend_rotations(neighbours, skip, smoothing, propagation, state);     // every iteration
//
// tie_directions: per tet, the horizontal direction that breaks the tie of straight-down faces
// (every horizontal axis turns them equally little): from the part's vertical axis out to the
// tet, so the arms of a T or the rim of a mushroom cap bend up and outwards together. With edge
// turns, a tet holding a flat overhang (a risky face within flat_overhang_deg of straight down)
// takes the direction towards the nearest edge of the input's flat-overhang region instead
// (overhang_boundary.h), and the axis of the turn that tilts it that way (edge_axis, else zero):
// within a small budget only a strip along a flat overhang's edges can reach the slope, as a bevel
// or keel, while tilting the whole underside about a far rim cannot. The region is the flat faces
// only, not all risky ones: an arch's flat crown turns towards its curved sides (a pointed arch),
// not towards its front and back.
//   Inputs: the input surface (mm), the domain, the tets' constraint pieces (local_step.h), the
//   input's unit rest normals (#F by 3) and risky flags (#F), the unit print direction, the
//   input's bbox diagonal (mm), the options. Output: #T unit tie directions, #T edge axes.
//
// tet_neighbours: face-adjacent tets (sharing three vertices) of the tets marked in `from`, and
// those tets as neighbours of theirs, as lists in ascending order: the blend only ever pairs a tet
// that holds surface faces with its neighbours. Inputs: T (#T by 4), the vertex count, #T marks.
//
// blend_rotations: L_t = (blended extra rotation) L_t for every tet not skipped. A risky tet
// blends its own R_t with the area-weighted quaternion mean of its risky neighbours' by
// `smoothing`; a safe tet next to risky ones takes `propagation` of their mean; a tet with no
// risky neighbour (or a share of 0) keeps its own R_t (identity for a safe tet). Reads only the
// local step's R_t and risky areas, so the result does not depend on the order of the tets.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"
#include "core/optimizer/local_step.h"
#include "core/optimizer/slimming_options.h"

namespace slim {

struct TieDirections {
  std::vector<Eigen::Vector3d> tie, edge_axis;  // #T each
};

TieDirections tie_directions(const Surface& input, const TetMesh& domain, const TetPieces& pieces,
                             const Points& rest_normals, const std::vector<bool>& risky, const Eigen::Vector3d& d,
                             double diag, const CoherenceOptions& coherence);

std::vector<std::vector<int>> tet_neighbours(const Tets& T, Eigen::Index vertex_count, const std::vector<bool>& from);

void blend_rotations(const std::vector<std::vector<int>>& neighbours, const std::vector<bool>& skip, double smoothing,
                     double propagation, LocalStepState& state);

}  // namespace slim
