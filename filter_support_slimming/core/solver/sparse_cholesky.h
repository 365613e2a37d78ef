// A sparse symmetric positive definite matrix, factored once and solved many times with three
// right-hand sides: the global step's linear algebra (arap.h), behind whichever backend is built.
//
//   SparseCholesky K(lower, options);     // analysis (METIS ordering) + numeric factorization
//   K.solve(b, x);                         // b: n by 3 -> x: n by 3, K x = b
//
// Inputs: the lower triangle of an n by n SPD matrix (Eigen column-major, int indices); options.
// Backends:
//   Cholmod            CHOLMOD's supernodal LL^T, ordered by METIS alone (on our 3D domains it
//                      always beats AMD, with far fewer nonzeros in L, docs/history/speed-earlier.md;
//                      CHOLMOD's default analysis would try AMD first). The back-substitution runs on its
//                      factor with SupernodalSolver (supernodal_solve.h), faster for three right-hand
//                      sides than CHOLMOD's own solve (own_supernodal_solve = false keeps that one,
//                      for comparison).
//   CholmodSimplicial  CHOLMOD's simplicial LL^T (no BLAS).
//   EigenLDLT          Eigen's SimplicialLDLT with AMD ordering: always available.
//   Auto               Cholmod when built with CHOLMOD (SLIM_HAVE_CHOLMOD), else EigenLDLT; a CHOLMOD
//                      backend in a build without it throws std::invalid_argument.
// BLAS runs on options.blas_threads threads inside CHOLMOD's calls (blas_threads.h), and CHOLMOD's
// OpenMP regions run serialized during the factorization: Debian's CHOLMOD opens them with a fixed
// team of 4 for its copies, and on two cores that oversubscription spends more in thread wake-ups
// than the extra threads save (docs/history/speed-earlier.md).
// Errors: the constructor throws std::runtime_error when the factorization fails (the matrix is not
// positive definite); solve returns false when the backend fails or the result is not finite.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace slim {

enum class CholeskyBackend { Auto, Cholmod, CholmodSimplicial, EigenLDLT };

struct SparseCholeskyOptions {
  CholeskyBackend backend = CholeskyBackend::Auto;
  int blas_threads = 1;              // see above; 0 leaves the process's BLAS setting alone
  bool own_supernodal_solve = true;  // Cholmod: SupernodalSolver rather than CHOLMOD's solve
};

class SparseCholesky {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  SparseCholesky(const Matrix& lower, const SparseCholeskyOptions& options);
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  // x = K^-1 rhs; false when the backend reports a failure or x is not finite.
  bool solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x) const;
  const std::string& backend_name() const;  // e.g. "CHOLMOD supernodal"
  static bool cholmod_available();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace slim
