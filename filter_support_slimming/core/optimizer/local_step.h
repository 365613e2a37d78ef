// The local step of the paper (§II), tet by tet: the nearest rotation M_t of each tet's current
// deformation and, for a tet that holds risky faces, the extra rotation R_t that makes them
// self-supporting (the exact minimal rotation, min_rotation.h, or one on K-means proxies,
// proxy_rotation.h). The caller then sets L_t = R_t M_t (coherence.h blends neighbours' R_t).
//
//   LocalStep step(mesh, embedding, on_plate, rest_normals, tau, ...);   // once
//   step.run(V, state);                                                 // every iteration
//
// Fixed inputs (LocalStep)
//   rest_inverse   #T 3 by 3: (V_t^0)^-1 in arap.h's edge basis
//   pieces         #T lists of (face, area mm²): the surface faces that constrain tet t, clipped
//                  to it (embedding.h), less the faces on the build plate and zero-area pieces.
//                  Every non-plate piece constrains, not only the risky ones, so a rotation that
//                  fixes one face never breaks a safe neighbour. Pieces whose normals lie within
//                  kPieceMergeTolerance are one constraint (near_repeats.h): the first of them
//                  stays and carries their area (a subdivided or flat surface puts hundreds of
//                  such faces in a tet).
//   rest_normals   #F by 3 unit normals of the input (zero rows for zero-area faces)
//   d, tau         unit print direction; tau = sin(alpha_max - margin): the step solves with a
//                  small angular margin and every measurement uses alpha_max, so the global step
//                  does not leave faces just short of the threshold
//   max_step       cap on each R_t's angle (radians): the global step is never asked for a jump
//                  it can only half follow
//   tie, edge_axis, edge_slack  the tie-break direction and edge-turn axis of every tet and the
//                  slack of an edge turn (coherence.h: tie_directions); zero axis: no edge turn
//   skip           #T, true for rigid-feature tets (rigid_features.h gives them their L)
// Per-iteration outputs (LocalStepState, #T each)
//   L           M_t, the rotation nearest to V_t^cur (V_t^0)^-1 (polar.h)
//   extra       R_t of the risky tets: the edge turn when it is feasible and costs at most
//               edge_slack more than the minimal turn, else the minimal turn, capped at max_step;
//               the identity when no rotation exists. Not written for other tets.
//   risky_area  the area of t's pieces risky after M_t (mm²); 0 marks a safe tet
//   ae_area     the area of t's pieces poorly represented by their proxy (AE, §IV-C; mm²)
// The rotations are computed from the rest normals turned by M_t, never from the deformed
// surface's normals: those already carry M_t, and turning them again would count it twice.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/domain/embedding.h"
#include "core/geometry/tet_mesh.h"
#include "core/rotation/proxy_rotation.h"

namespace slim {

using TetPieces = std::vector<std::vector<std::pair<int, double>>>;  // #T lists of (face, area)

// Pieces whose unit normals lie this close (a chord, about radians) are one constraint. A rotation
// that makes the kept one safe leaves the others at most this far (in n·d) past the threshold:
// 6e-5 degrees, against the slicer's own 1° and the step's aim of 10° past. Faces of one plane
// differ by more than the minimal rotation's own tolerance (1e-12) once their vertices were stored
// as floats (as MeshLab stores a subdivided mesh): merged at that tolerance, a dense subdivided
// part keeps its near-copies of one normal as separate constraints and its local step is slower;
// merged here, the step is faster and the figures do not change beyond rounding
// (docs/history/speed.md).
inline constexpr double kPieceMergeTolerance = 1e-6;

// The pieces as described above; plate: #F, the faces resting on the build plate.
TetPieces constraint_pieces(const Embedding& embedding, Eigen::Index tets, const std::vector<bool>& plate,
                            const Points& rest_normals);

struct LocalStepState {
  std::vector<Eigen::Matrix3d> L, extra;
  std::vector<double> risky_area, ae_area;
};

struct LocalStep {
  const Tets* T = nullptr;
  std::vector<Eigen::Matrix3d> rest_inverse;
  TetPieces pieces;
  Points rest_normals;
  Eigen::Vector3d d = Eigen::Vector3d::UnitZ();
  double tau = 0.0, max_step = 0.0, edge_slack = 0.0;
  std::vector<Eigen::Vector3d> tie, edge_axis;
  std::vector<bool> skip;
  ProxyOptions proxies;

  // The rest inverses of `rest` (T is borrowed: it must outlive the step); everything else is
  // set by the caller.
  void set_rest(const TetMesh& rest);
  // L, extra, risky_area, ae_area for positions V (#DV by 3), in parallel over the tets.
  void run(const Points& V, LocalStepState& state) const;
  // Sized for the tets, L filled with identities (so its pages are set up with the rest of the
  // precomputation rather than in the first iteration).
  LocalStepState make_state() const;
};

}  // namespace slim
