// Keeping the part's volume through the global step: the enclosed volume of the embedded surface
// held at a target by a uniform pressure on it, the Lagrange step of the constraint
// Vol(V) = target on top of the ARAP minimiser.
//
//   keep_volume(arap, embedding, faces, target, proposed)
//
// Inputs
//   arap       the factored global step (arap.h), for the response to the pressure.
//   embedding  the surface in the domain (embedding.h); faces: the surface's #F by 3 triangles.
//   target     the volume to keep (mm³): the input's signed enclosed volume (surface.h).
//   proposed   #DV by 3, the global step's minimiser; moved in place.
// Output: proposed + lambda u, u = K^-1 (dVol/dV) the displacement under a unit pressure (the
//   volume's gradient is the area-weighted normals of the surface, taken to the domain vertices
//   through the barycentric weights), lambda found by Newton's method (the volume is a cubic in
//   it) until the volume is within 1e-9 of the target or after 4 steps. Returns lambda (0 when the
//   pressure cannot change the volume, e.g. every vertex held).
// Why a pressure: ARAP's targets are rotations, which keep each tet's volume, but the blend of
// incompatible rotations compresses: the overhangs bent up were carved into the part (the coherent
// method lost 7.5% of the volume of the corpus's organic models). The pressure puts that volume
// back where the part is softest, spread by the same stiffness that blends the rotations.
#pragma once

#include "core/arap.h"
#include "core/embedding.h"
#include "core/surface.h"

namespace slim {

// d Vol / d V for the embedded surface (#DV by 3, mm²), at domain positions V.
Points embedded_volume_gradient(const Embedding& embedding, const Triangles& faces, const Points& surface_V,
                                Eigen::Index domain_vertices);

double keep_volume(const ArapSolver& arap, const Embedding& embedding, const Triangles& faces, double target,
                   Points& proposed);

}  // namespace slim
