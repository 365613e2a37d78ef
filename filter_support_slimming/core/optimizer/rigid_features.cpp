#include "core/optimizer/rigid_features.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "core/rotation/polar.h"
#include "core/rotation/proxy_rotation.h"
#include "core/solver/arap.h"
#include "core/utilities/union_find.h"

namespace slim {

namespace {

// Connected components of the marked faces over shared vertices, numbered by their first face;
// -1 for unmarked faces.
std::vector<int> feature_components(const Surface& s, const std::vector<bool>& marked, int& count) {
  UnionFind sets(static_cast<int>(s.V.rows()));
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (marked[static_cast<size_t>(f)])
      for (int k = 1; k < 3; ++k) sets.join(s.F(f, k), s.F(f, 0));
  std::vector<int> label(static_cast<size_t>(s.V.rows()), -1), face_feature(static_cast<size_t>(s.F.rows()), -1);
  count = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    if (!marked[static_cast<size_t>(f)]) continue;
    int& l = label[static_cast<size_t>(sets.find(s.F(f, 0)))];
    if (l < 0) l = count++;
    face_feature[static_cast<size_t>(f)] = l;
  }
  return face_feature;
}

}  // namespace

RigidFeatures::RigidFeatures(const Surface& input, const std::vector<bool>& marks, const Embedding& emb,
                             const TetMesh& domain)
    : tet_feature_(static_cast<size_t>(domain.T.rows()), -1), vertex_(static_cast<size_t>(domain.V.rows()), -1) {
  if (marks.empty()) return;
  int count = 0;
  const std::vector<int> face_feature = feature_components(input, marks, count);
  tets_.resize(static_cast<size_t>(count));
  for (Eigen::Index t = 0; t < domain.T.rows(); ++t) {
    int& feature = tet_feature_[static_cast<size_t>(t)];
    for (int p = emb.tet_face_offsets(t); p < emb.tet_face_offsets(t + 1) && feature < 0; ++p)
      feature = face_feature[static_cast<size_t>(emb.tet_faces(p))];
    if (feature < 0) continue;
    tets_[static_cast<size_t>(feature)].push_back(static_cast<int>(t));
    for (int k = 0; k < 4; ++k) {
      int& owner = vertex_[static_cast<size_t>(domain.T(t, k))];
      owner = owner < 0 ? feature : std::min(owner, feature);
    }
  }
}

std::vector<bool> RigidFeatures::tet_flags() const {
  std::vector<bool> flags(tet_feature_.size());
  for (size_t t = 0; t < flags.size(); ++t) flags[t] = tet_feature_[t] >= 0;
  return flags;
}

void RigidFeatures::fit(const Points& V, const Eigen::VectorXd& weights, const LocalStep& local,
                        LocalStepState& state) const {
  for (const std::vector<int>& tets : tets_) {
    Eigen::Matrix3d Qsum = Eigen::Matrix3d::Zero();
    for (int t : tets)
      Qsum += weights(t) * (edge_matrix(V, local.T->row(t)) * local.rest_inverse[static_cast<size_t>(t)]);
    const Eigen::Matrix3d Mf = closest_rotation(Qsum);
    std::vector<Eigen::Vector3d> ns;
    std::vector<double> as;
    for (int t : tets)
      for (const auto& [face, area] : local.pieces[static_cast<size_t>(t)]) {
        ns.push_back(Mf * local.rest_normals.row(face).transpose());
        as.push_back(area);
      }
    Eigen::Matrix3d Rf = Eigen::Matrix3d::Identity();
    if (!ns.empty()) {
      Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(ns.size()));
      Eigen::VectorXd areas(static_cast<Eigen::Index>(as.size()));
      for (size_t i = 0; i < ns.size(); ++i) {
        normals.col(static_cast<Eigen::Index>(i)) = ns[i];
        areas(static_cast<Eigen::Index>(i)) = as[i];
      }
      const ProxyRotation pr = proxy_rotation(normals, areas, local.d, local.tau, {}, local.proxies);
      if (!pr.undefined && pr.solution.feasible)
        Rf = Eigen::AngleAxisd(std::min(pr.solution.angle, local.max_step), pr.solution.axis).toRotationMatrix();
    }
    for (int t : tets) state.L[static_cast<size_t>(t)] = Rf * Mf;
  }
}

}  // namespace slim
