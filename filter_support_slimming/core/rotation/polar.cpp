#include "core/rotation/polar.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace slim {

namespace {

// Newton steps go to the SVD beyond this Frobenius condition number ||Q|| ||Q^-1||: there the
// first inverse loses more than 6 of the 16 digits and a flat tet is better served by the SVD.
constexpr double kMaxCondition = 1e6;
constexpr double kMinRelativeDet = 1e-10;
// Once converging quadratically, a step of size s leaves the new iterate about s^2 / 2 from the
// answer: below 1e-8 that is under the rounding error, so the new iterate is returned.
constexpr double kConvergedStep = 1e-8;
// Past this step size the scaling only slows the final quadratic steps down (Higham), so it stops.
constexpr double kUnscaledStep = 1e-2;
constexpr int kMaxIterations = 20;

// Columns b x c, c x a, a x b of X = [a b c]: X^-T times det X.
inline Eigen::Matrix3d cofactor(const Eigen::Matrix3d& X) {
  Eigen::Matrix3d C;
  C.col(0) = X.col(1).cross(X.col(2));
  C.col(1) = X.col(2).cross(X.col(0));
  C.col(2) = X.col(0).cross(X.col(1));
  return C;
}

}  // namespace

Eigen::Matrix3d closest_rotation_svd(const Eigen::Matrix3d& Q) {
  if (!Q.allFinite()) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(Q, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d& W = svd.matrixV();
  // Singular values come sorted, largest first, so column 2 belongs to the smallest.
  if (U.determinant() * W.determinant() < 0.0) U.col(2) = -U.col(2);
  return U * W.transpose();
}

Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& Q) {
  if (!Q.allFinite()) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Matrix3d X = Q;
  Eigen::Matrix3d C = cofactor(X);
  double det = X.col(0).dot(C.col(0));
  double x2 = X.squaredNorm(), c2 = C.squaredNorm();  // squared norms: no square roots needed
  // det and C carry absolute rounding errors of about 1e-16 ||Q||^3 and 1e-16 ||Q||^2, so the
  // condition estimate ||Q|| ||C|| / det is trusted only when det is far above that noise (a
  // rank-1 Q can show a tiny positive det and a "moderate" estimate). Written without dividing.
  const double norm = std::sqrt(x2);
  if (!(det > kMinRelativeDet * norm * x2) || x2 * c2 > kMaxCondition * kMaxCondition * det * det)
    return closest_rotation_svd(Q);

  bool scaled = true;
  for (int it = 0; it < kMaxIterations; ++it) {
    // Frobenius scaling z = sqrt(||X^-1|| / ||X||) pulls the singular values towards 1 at once;
    // ||X^-1|| = ||C|| / det.
    const double inv_det = 1.0 / det;
    const double z = scaled ? std::sqrt(std::sqrt(c2 * inv_det * inv_det / x2)) : 1.0;
    const Eigen::Matrix3d next = (0.5 * z) * X + (0.5 * inv_det / z) * C;
    const double step2 = (next - X).squaredNorm();
    X = next;
    if (step2 <= kConvergedStep * kConvergedStep) return X;
    if (step2 <= kUnscaledStep * kUnscaledStep) scaled = false;
    C = cofactor(X);
    det = X.col(0).dot(C.col(0));
    if (scaled) {
      x2 = X.squaredNorm();
      c2 = C.squaredNorm();
    }
  }
  return closest_rotation_svd(Q);
}

}  // namespace slim
