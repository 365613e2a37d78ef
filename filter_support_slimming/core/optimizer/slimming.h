// Support slimming: the paper's local/global shape optimizer (§II–IV), end to end.
//
// In:  a Surface (#V by 3 positions in mm, #F by 3 outward-oriented triangles) and options.
// Out: the deformed Surface (same #V, same F: the topology never changes), in the input's frame,
//      with per-iteration statistics and the overhang report of the result.
//
// slim_supports is the driver: it checks the input once, builds the domain (embedded_domain.h)
// and a SupportSlimmer (support_slimmer.h: the precomputation; step() is one iteration), runs the
// iterations under the stopping rule below and keeps the best iterate (result_choice.h); it does
// so at each voxel resolution of the ladder and keeps the run whose result the support model
// prefers (resolution_ladder.h).
//
// Each iteration:
//   local step   for every tet t:  M_t = polar(V_t^cur (V_t^0)^-1)  (nearest rotation, det +1).
//                A tet holding risky faces turns their rest normals by M_t, asks min_rotation for
//                the smallest R_t that makes them all self-supporting (K-means proxies when no
//                exact answer exists) and sets L_t = R_t M_t; every other tet keeps L_t = M_t
//                (local_step.h; the coherent method blends neighbours' R_t, coherence.h; rigid
//                features share one L, rigid_features.h).
//   global step  V = argmin sum_t w_t ||V_t - L_t V_t^0||_F^2 with the plate vertices held
//                (arap.h: factored once, back-substituted every iteration).
//   guards       the plate, the deviation budget and the inversion guard (step_guards.h).
// The surface follows the domain through fixed barycentric coordinates (embedding.h).
//
// Stopping: the first of  max_iterations;  the overhang deficit (overhang.h: risky area weighted
// by how far each face is from safe) no longer falling by stall_tolerance of its initial value;
// the paper's inversion guard cutting a step back; cancel. The deviation budget (the largest
// vertex displacement, % of the bbox diagonal or a length) is a constraint, not a stop: after every
// global step the part of the step that would take a domain vertex past the budget is rolled
// back, so no surface vertex ever moves further; a rigid feature that reaches it holds there, in
// one piece, while the rest goes on.
// The result is the iterate that needs the least support (result_choice.h: by the support model,
// or in the paper's method the shadow volume of overhang.h), then the least risky area, the later
// one on ties, among the iterates with no more risky area than the input; the input itself when
// no iterate beats it (by the model: by at least CoherenceOptions::min_support_saving_pct, over
// the grid phases and at the slicer's own). So
// neither the risky area nor the support estimate of the result exceeds the input's.
#pragma once

#include "core/geometry/surface.h"
#include "core/optimizer/slimming_options.h"
#include "core/optimizer/slimming_result.h"

namespace slim {

// Throws std::invalid_argument for bad input or options (with the reason and what to change),
// including faces that are not consistently oriented; Cancelled when progress returns false;
// std::runtime_error for a numerical failure. An inside-out closed mesh is not an error: it is
// computed turned over (SlimmingResult::inside_out).
SlimmingResult slim_supports(const Surface& input, const SlimmingOptions& options = {});

// The mesh refusals of slim_supports, on their own, so that a caller can tell a bad mesh from bad
// options or a failed run before any work: no faces, a face indexing outside the vertices, a
// non-finite coordinate (check_surface), faces not consistently oriented, or zero extent. Throws
// std::invalid_argument with the reason; returns the mesh's edge topology.
EdgeTopology check_slimming_input(const Surface& input);

}  // namespace slim
