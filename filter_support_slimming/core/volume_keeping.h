// Keeping the part's volume through the global step: the enclosed volume of the embedded surface
// held at a target by a uniform pressure on it, the Lagrange step of the constraint
// Vol(V) = target on top of the ARAP minimiser.
//
//   const Points load = volume_load(embedding, faces, V_start);          // before the global step
//   Points u;
//   Points proposed = arap.solve_with_response(L, V_held, load, u);      // one back-substitution
//   keep_volume(embedding, faces, target, u, proposed);
//
// Inputs
//   embedding  the surface in the domain (embedding.h); faces: the surface's #F by 3 triangles.
//   V_start    #DV by 3, the domain's positions at the start of the step (mm).
//   target     the volume to keep (mm³): the input's signed enclosed volume (surface.h).
//   response   #DV by 3, u = K^-1 load (arap.h): the displacement under a unit pressure.
//   proposed   #DV by 3, the global step's minimiser; moved in place.
// Output: volume_load is dVol/dV at V_start (#DV by 3, mm²: the area-weighted normals of the
//   surface, taken to the domain vertices through the barycentric weights). keep_volume moves
//   proposed to proposed + lambda u and returns lambda (0 when the pressure cannot change the
//   volume, e.g. every vertex held). The volume is exactly a cubic in lambda, whose coefficients
//   take one pass over the faces; Newton's method on it, from 0, until the volume is within 1e-12
//   of the target or after 20 steps. (Newton on the surface itself took a pass over the faces
//   for the volume and one for its gradient per step: at 940k faces most of the global step.)
// Why the pressure's direction is taken at the start of the step and not at the minimiser: its
//   response then shares the global step's back-substitution (six right-hand sides in one sweep:
//   22 ms against two sweeps of three, 32 ms, on a 50k-vertex domain, bench/arap_bench); with
//   steps of a few degrees the surface's normals barely differ, and Newton's method still meets
//   the target exactly.
// Why a pressure: ARAP's targets are rotations, which keep each tet's volume, but the blend of
// incompatible rotations compresses: the overhangs bent up were carved into the part (the coherent
// method lost 7.5% of the volume of the corpus's organic models). The pressure puts that volume
// back where the part is softest, spread by the same stiffness that blends the rotations.
#pragma once

#include "core/embedding.h"
#include "core/surface.h"

namespace slim {

// d Vol / d V for the embedded surface (#DV by 3, mm²), at domain positions V.
Points embedded_volume_gradient(const Embedding& embedding, const Triangles& faces, const Points& surface_V,
                                Eigen::Index domain_vertices);

Points volume_load(const Embedding& embedding, const Triangles& faces, const Points& V_start);

double keep_volume(const Embedding& embedding, const Triangles& faces, double target, const Points& response,
                   Points& proposed);

}  // namespace slim
