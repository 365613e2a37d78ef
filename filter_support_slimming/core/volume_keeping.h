// Keeping the part's volume through the global step: the enclosed volume of the embedded surface
// held at a target by a uniform pressure on it, the Lagrange step of the constraint
// Vol(V) = target on top of the ARAP minimiser.
//
//   const VolumeKeeping volume(embedding, faces, domain_vertices);      // once per domain
//   const Points load = volume.load(V_start);                           // before the global step
//   Points u;
//   Points proposed = arap.solve_with_response(L, V_held, load, u);      // one back-substitution
//   volume.keep(target, u, proposed);
//
// The free functions volume_load and keep_volume do the same with the set-up made on the spot.
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
// Cost per step: one pass over the faces for the load and one for the cubic, both on the OpenMP
//   threads. The set-up lists each surface vertex's face corners in the order a single pass over
//   the faces would add them, so the load's bits and the cubic's are those of that single pass on
//   any thread count (6 #F integers; at 1.1M faces the two passes took 30 ms a step on one
//   thread, the most serial part of the step).
// Why a pressure: ARAP's targets are rotations, which keep each tet's volume, but the blend of
// incompatible rotations compresses: the overhangs bent up were carved into the part (the coherent
// method lost 7.5% of the volume of the corpus's organic models). The pressure puts that volume
// back where the part is softest, spread by the same stiffness that blends the rotations.
#pragma once

#include <array>
#include <vector>

#include "core/embedding.h"
#include "core/surface.h"

namespace slim {

class VolumeKeeping {
 public:
  // embedding: the surface's (embedding.h); faces: its #F by 3 triangles; domain_vertices: #DV.
  // Both are read by reference on every call: they must outlive the object, unchanged.
  // Throws std::invalid_argument when a face or the embedding names a vertex out of range.
  // The calls reuse the object's buffers (the surface's positions, by columns and by rows), so
  // one object serves one thread at a time.
  VolumeKeeping(const Embedding& embedding, const Triangles& faces, Eigen::Index domain_vertices);
  Points load(const Points& V_start);                                   // volume_load()
  double keep(double target, const Points& response, Points& proposed);  // keep_volume()

 private:
  using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  // The embedded surface at domain positions V, about its centroid, by rows (a face's corners are
  // rows far apart: one cache line each so); `by_columns` is the surface as embedded_positions
  // gives it, whose centroid this is.
  void centred_surface(const Points& V, Points& by_columns, RowPoints& out) const;
  const Embedding& embedding_;
  const Triangles& F_;
  Eigen::Index domain_vertices_;
  // Per surface vertex, its face corners in face order: the corner's next and last vertex.
  std::vector<int> corner_begin_;
  std::vector<std::array<int, 2>> corner_others_;
  // Buffers kept from call to call: fresh ones cost a page fault every 4 kB, every step.
  Points S_;
  RowPoints P_, Q_;
  Eigen::Matrix<double, 4, Eigen::Dynamic> terms_;
};

Points volume_load(const Embedding& embedding, const Triangles& faces, const Points& V_start);

double keep_volume(const Embedding& embedding, const Triangles& faces, double target, const Points& response,
                   Points& proposed);

}  // namespace slim
