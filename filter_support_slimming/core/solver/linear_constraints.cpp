#include "core/solver/linear_constraints.h"

#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace slim {

LinearConstraints::LinearConstraints(std::vector<Eigen::MatrixXd> C,
                                     const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& solve)
    : C_(std::move(C)) {
  const int m = size();
  for (const Eigen::MatrixXd& Ck : C_)
    if (Ck.rows() != C_.front().rows() || Ck.cols() != C_.front().cols())
      throw std::invalid_argument("LinearConstraints: every constraint must have the unknowns' shape");
  if (m == 0) return;
  G_.reserve(C_.size());
  for (const Eigen::MatrixXd& Ck : C_) G_.push_back(solve(Ck));
  Eigen::MatrixXd S(m, m);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b) S(a, b) = C_[static_cast<size_t>(a)].cwiseProduct(G_[static_cast<size_t>(b)]).sum();
  S = 0.5 * (S + S.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const Eigen::VectorXd lambda = eig.eigenvalues();
  const double largest = m > 0 ? lambda.cwiseAbs().maxCoeff() : 0.0;
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(m);
  for (int k = 0; k < m; ++k)
    if (lambda(k) > 1e-12 * largest) inverse(k) = 1.0 / lambda(k);
  S_inverse_ = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::VectorXd LinearConstraints::values(const Eigen::Ref<const Eigen::MatrixXd>& x) const {
  Eigen::VectorXd v(size());
  for (int k = 0; k < size(); ++k) {
    const Eigen::MatrixXd& Ck = C_[static_cast<size_t>(k)];
    if (x.rows() != Ck.rows() || x.cols() != Ck.cols())
      throw std::invalid_argument("LinearConstraints: the unknowns do not have the constraints' shape");
    v(k) = Ck.cwiseProduct(x).sum();
  }
  return v;
}

void LinearConstraints::project(Eigen::Ref<Eigen::MatrixXd> x, const Eigen::VectorXd& c) const {
  if (c.size() != size()) throw std::invalid_argument("LinearConstraints: expected one value per constraint");
  if (size() == 0) return;
  const Eigen::VectorXd lambda = S_inverse_ * (values(x) - c);
  for (int k = 0; k < size(); ++k) x -= lambda(k) * G_[static_cast<size_t>(k)];
}

}  // namespace slim
