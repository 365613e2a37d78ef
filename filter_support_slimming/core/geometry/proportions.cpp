#include "core/geometry/proportions.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/SVD>

namespace slim {
namespace {

double change_pct(double before, double after) { return before > 0.0 ? 100.0 * (after / before - 1.0) : 0.0; }

double extent_along(const Points& V, const Eigen::Vector3d& d) {
  const Eigen::VectorXd h = V * d;
  return h.maxCoeff() - h.minCoeff();
}

long folded_faces(const Surface& input, const Points& result_V) {
  long folded = 0;
  for (Eigen::Index f = 0; f < input.F.rows(); ++f) {
    const Eigen::Vector3d a = face_cross(input.V, input.F, f), b = face_cross(result_V, input.F, f);
    if (a.squaredNorm() > 0.0 && b.squaredNorm() > 0.0 && a.dot(b) < 0.0) ++folded;
  }
  return folded;
}

// 100 max |sigma - 1| of I + B, B the least-norm least-squares fit of the displacements U on the
// centred positions Xc (row vectors: Xc B ≈ U), by the normal equations, 3 by 3: a direction in
// which the input's extent is below 1e-9 of its largest is left out of the fit.
double affine_departure_pct(const Points& X, const Points& Y) {
  const Eigen::RowVector3d cx = X.colwise().mean(), cy = Y.colwise().mean();
  const Points Xc = X.rowwise() - cx;
  const Points U = (Y.rowwise() - cy) - Xc;
  const Eigen::Matrix3d G = Xc.transpose() * Xc, R = Xc.transpose() * U;
  const Eigen::Matrix3d B = affine_fit_solve(G, R);
  const Eigen::Vector3d sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(Eigen::Matrix3d::Identity() + B).singularValues();
  return 100.0 * (sigma.array() - 1.0).abs().maxCoeff();
}

}  // namespace

Eigen::Matrix3d affine_fit_solve(const Eigen::Matrix3d& G, const Eigen::Matrix3d& R) {
  Eigen::JacobiSVD<Eigen::Matrix3d> gram(G, Eigen::ComputeFullU | Eigen::ComputeFullV);
  gram.setThreshold(1e-18);  // of the largest singular value of G: extents below 1e-9 of the largest
  return gram.solve(R);
}

Proportions proportions(const Surface& input, const Points& result_V, const Eigen::Vector3d& d) {
  if (result_V.rows() != input.V.rows() || !result_V.allFinite())
    throw std::invalid_argument("proportions: the result must give finite positions for every vertex of the input");
  Proportions p;
  if (input.V.rows() == 0) return p;
  const Eigen::RowVector3d before = input.V.colwise().maxCoeff() - input.V.colwise().minCoeff();
  const Eigen::RowVector3d after = result_V.colwise().maxCoeff() - result_V.colwise().minCoeff();
  for (int axis = 0; axis < 3; ++axis) p.extent_change_pct(axis) = change_pct(before(axis), after(axis));
  p.height_change_pct = change_pct(extent_along(input.V, d), extent_along(result_V, d));
  p.folded_faces = folded_faces(input, result_V);
  p.affine_departure_pct = affine_departure_pct(input.V, result_V);
  return p;
}

}  // namespace slim
