#include "core/optimizer/rigid_proportions.h"

#include "core/geometry/proportions.h"

namespace slim {

std::vector<Points> stretch_constraints(const Surface& input, const Embedding& embedding, Eigen::Index domain_vertices) {
  const Points Xc = input.V.rowwise() - input.V.colwise().mean();
  const Eigen::Matrix3d G_inverse = affine_fit_solve(Xc.transpose() * Xc, Eigen::Matrix3d::Identity());
  const Points Q = Xc * G_inverse;  // #V by 3: B = Q^T (Y - X)
  Points Z = Points::Zero(domain_vertices, 3);  // E^T Q
  for (Eigen::Index v = 0; v < Q.rows(); ++v)
    for (int k = 0; k < 4; ++k) Z.row(embedding.vertex_nodes(v, k)) += embedding.vertex_bary(v, k) * Q.row(v);
  std::vector<Points> C;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      Points Cij = Points::Zero(domain_vertices, 3);
      Cij.col(j) += Z.col(i);  // B_ij = sum_v Z_vi (V_vj - V0_vj)
      Cij.col(i) += Z.col(j);  // B_ji
      C.push_back(std::move(Cij));
    }
  return C;
}

Eigen::VectorXd constraint_values(const std::vector<Points>& C, const Points& V) {
  Eigen::VectorXd c(static_cast<Eigen::Index>(C.size()));
  for (size_t k = 0; k < C.size(); ++k) c(static_cast<Eigen::Index>(k)) = C[k].cwiseProduct(V).sum();
  return c;
}

}  // namespace slim
