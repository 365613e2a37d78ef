// Rigid features (paper §IV-B): connected pieces of marked faces that each move as one rigid body,
// so that a part the user cares about (an arm, a face, a logo) keeps its shape.
//
//   RigidFeatures features(input, marks, embedding, domain);      // once
//   features.fit(V, weights, local, state);                       // every iteration, after the blend
//
// Inputs
//   input      the surface (#V by 3, #F by 3); marks: #F, true for a face of a feature (empty:
//              no features).
//   embedding  the surface in the domain (embedding.h); domain: its tet mesh (#DV, #DT).
// Outputs
//   count        the number of features: the connected components of the marked faces over shared
//                vertices, numbered in the order of their first face.
//   tet_feature  #DT: the feature of the first marked face a tet holds (its face pieces in order),
//                -1 for none. Such a tet's L comes from its feature, not from the local step.
//   tets         per feature, its tets in ascending order (computed once; no per-iteration scan).
//   vertex_feature  #DV: the feature of each vertex of a feature tet (the lowest one where
//                features meet), -1 for the others; the guards never move a feature's vertices
//                alone.
// fit: for every feature, M_f = the rotation nearest to sum_t w_t V_t^cur (V_t^0)^-1 over its tets
// (w: the global step's weights), R_f = the minimal rotation of all its constraint pieces' rest
// normals turned by M_f (on proxies when no exact one exists; the identity when none does),
// capped at the local step's max_step; L_t = R_f M_f for all its tets.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/domain/embedding.h"
#include "core/geometry/surface.h"
#include "core/geometry/tet_mesh.h"
#include "core/optimizer/local_step.h"

namespace slim {

class RigidFeatures {
 public:
  RigidFeatures(const Surface& input, const std::vector<bool>& marks, const Embedding& embedding, const TetMesh& domain);

  int count() const { return static_cast<int>(tets_.size()); }
  const std::vector<int>& tet_feature() const { return tet_feature_; }
  const std::vector<int>& tets(int feature) const { return tets_[static_cast<size_t>(feature)]; }
  const std::vector<int>& vertex_feature() const { return vertex_; }
  // tet_feature() >= 0 as flags, for the local step's `skip`.
  std::vector<bool> tet_flags() const;

  void fit(const Points& V, const Eigen::VectorXd& weights, const LocalStep& local, LocalStepState& state) const;

 private:
  std::vector<int> tet_feature_;
  std::vector<std::vector<int>> tets_;
  std::vector<int> vertex_;
};

}  // namespace slim
