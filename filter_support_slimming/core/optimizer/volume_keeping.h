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
//   volume, e.g. every vertex held). The volume is exactly a cubic in lambda; Newton's method on
//   it, from 0, until the volume is within 1e-12 of the target or after 20 steps.
// Why the pressure's direction is taken at the start of the step and not at the minimiser: its
//   response then shares the global step's back-substitution (six right-hand sides in one sweep
//   cost less than two sweeps of three: docs/speed.md, bench/arap_bench); with
//   steps of a few degrees the surface's normals barely differ, and Newton's method still meets
//   the target exactly.
// How, on the domain alone: the surface is the domain's vertices through fixed weights, so its
//   volume (about its centroid, a fixed combination of them too) is a fixed cubic form of the
//   domain's positions, 1/6 sum of c_ijk det[V_i, V_j, V_k] over triples of the nodes of the
//   tets the faces lie in. The set-up finds the c_ijk once (the constructor says how); each step
//   then reads the domain's vertices and not the surface's. Where a group of faces would need
//   more than four triples a face (a coarse surface in a fine domain: one face's corners in three
//   tets apart, 220 triples), those faces are summed face by face instead, their corners made
//   from the domain on the spot.
// Cost: the set-up groups the faces by the tets their corners lie in (one pass, a hash of the
//   faces across tets), sums each group's minors over its faces on the threads, and merges the
//   triples that groups share (a counting sort by node); each step is then one pass over the
//   triples for the load and one for the cubic. A dense surface in a coarse domain goes mostly by
//   its groups' triples, so a step costs the domain's size and not the surface's; a coarse surface
//   in a fine domain goes face by face, as fast as summing the faces (docs/history/speed.md,
//   bench/slimming_stages). Sums run in face order within a group, in group order across groups
//   and in face order for the faces by themselves: the same bits on any thread count.
// Why a pressure: ARAP's targets are rotations, which keep each tet's volume, but the blend of
// incompatible rotations compresses: the overhangs bent up were carved into the part, and organic
// parts lost a visible share of their volume (docs/history/slicer-frontier-baseline.md). The
// pressure puts that volume back where the part is softest, spread by the same stiffness that
// blends the rotations.
#pragma once

#include <array>
#include <vector>

#include "core/domain/embedding.h"
#include "core/geometry/surface.h"

namespace slim {

class VolumeKeeping {
 public:
  // embedding: the surface's (embedding.h); faces: its #F by 3 triangles; domain_vertices: #DV.
  // Both are read here only. Throws std::invalid_argument when a face or the embedding names a
  // vertex out of range. The calls reuse the object's buffers (the domain's centred positions),
  // so one object serves one thread at a time.
  VolumeKeeping(const Embedding& embedding, const Triangles& faces, Eigen::Index domain_vertices);
  Points load(const Points& V_start);                                   // volume_load()
  double keep(double target, const Points& response, Points& proposed);  // keep_volume()

  // Three domain nodes i < j < k and the weight c_ijk of det[V_i, V_j, V_k] in the volume (the
  // constructor says how it is made).
  struct Triple {
    std::array<int, 3> nodes;
    double coefficient;
  };

 private:
  using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  // Domain positions V less the embedded surface's centroid, by rows.
  void centred(const Points& V, RowPoints& out) const;
  Eigen::Index domain_vertices_;
  // A face taken face by face: each corner's four nodes and weights.
  struct Corners {
    std::array<std::array<int, 4>, 3> nodes;
    std::array<std::array<double, 4>, 3> weights;
    Eigen::RowVector3d at(int corner, const RowPoints& V) const;  // the corner at positions V
  };
  Eigen::VectorXd centroid_weights_;  // #DV: the surface's centroid is their sum of V
  // The volume: 1/6 (sum of c_ijk det[V_i, V_j, V_k] + sum over faces_ of det[x_a, x_b, x_c]).
  std::vector<Triple> triples_;
  std::vector<Corners> faces_;
  // Buffers kept from call to call: fresh ones cost a page fault every 4 kB, every step.
  RowPoints P_, Q_;
};

Points volume_load(const Embedding& embedding, const Triangles& faces, const Points& V_start);

double keep_volume(const Embedding& embedding, const Triangles& faces, double target, const Points& response,
                   Points& proposed);

}  // namespace slim
