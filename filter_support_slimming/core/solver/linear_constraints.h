// Linear equality constraints on a least-squares solve whose matrix is already factored: the
// constrained minimiser is the unconstrained one plus a Lagrange correction in the span of a few
// precomputed solves, so the factorization never changes (arap.h uses it for its constraints).
//
//   minimise 1/2 x^T K x - b^T x   subject to   <C_k, x> = c_k,  k = 0..m-1
//   x = y - sum_k G_k lambda_k,  y = K^-1 b,  G_k = K^-1 C_k,  S lambda = <C, y> - c,  S_ab = <C_a, G_b>
//
//   LinearConstraints cons(C, solve);   // precomputation: one solve per constraint
//   cons.project(x, c);                 // per solve: m inner products, m axpys
//   cons.project(dx, zeros)             // a load's response stays within the constraints
//
// Inputs
//   C      m matrices, each #x by k (the unknowns as rows, k columns of right-hand sides that K
//          acts on independently: k = 3 for x, y, z), <A, B> = sum of their entrywise products.
//   solve  K^-1 of a #x by k matrix (the factored matrix's back-substitution).
// Outputs: project() corrects x (#x by k) in place so that <C_k, x> = c_k (m values) to rounding.
// Constraints that are (nearly) dependent on the others are held only as far as the rest hold
// them: S is inverted on its eigenvalues above 1e-12 of its largest (none: no correction).
// Errors: std::invalid_argument for mismatched sizes.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

namespace slim {

class LinearConstraints {
 public:
  LinearConstraints(std::vector<Eigen::MatrixXd> C, const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& solve);

  void project(Eigen::Ref<Eigen::MatrixXd> x, const Eigen::VectorXd& c) const;
  // <C_k, x> for every k (m values).
  Eigen::VectorXd values(const Eigen::Ref<const Eigen::MatrixXd>& x) const;
  int size() const { return static_cast<int>(C_.size()); }

 private:
  std::vector<Eigen::MatrixXd> C_, G_;
  Eigen::MatrixXd S_inverse_;  // m by m pseudo-inverse of S
};

}  // namespace slim
