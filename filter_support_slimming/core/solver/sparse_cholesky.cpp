#include "core/solver/sparse_cholesky.h"

#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "core/platform/blas_threads.h"
#include "core/platform/parallel_for.h"

#ifdef SLIM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>

#include "core/solver/supernodal_solve.h"
#endif

namespace slim {

namespace {

using Matrix = SparseCholesky::Matrix;

template <class Solver>
std::unique_ptr<Solver> factor_with(const Matrix& K) {
  auto s = std::make_unique<Solver>();
  s->compute(K);
  if (s->info() != Eigen::Success)
    throw std::runtime_error(
        "ArapSolver: the factorization of the global step failed (matrix not positive definite: "
        "check for degenerate tets or weights)");
  return s;
}

#ifdef SLIM_HAVE_CHOLMOD
// CHOLMOD's supernodal LL^T through Eigen, with the factor itself in reach for SupernodalSolver.
class CholmodSupernodal : public Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower> {
 public:
  bool view(SupernodalFactor& out) const { return supernodal_view(m_cholmodFactor, out); }
};

// METIS alone (see sparse_cholesky.h); a CHOLMOD built without METIS fails that analysis, and the
// default one is used then.
template <class Solver>
std::unique_ptr<Solver> factor_with_metis(const Matrix& K) {
  auto s = std::make_unique<Solver>();
  s->cholmod().nmethods = 1;
  s->cholmod().method[0].ordering = CHOLMOD_METIS;
  s->compute(K);
  if (s->info() == Eigen::Success) return s;
  return factor_with<Solver>(K);
}
#endif

}  // namespace

struct SparseCholesky::Impl {
  SparseCholeskyOptions options;
  std::string backend;
  std::unique_ptr<Eigen::SimplicialLDLT<Matrix, Eigen::Lower>> ldlt;
#ifdef SLIM_HAVE_CHOLMOD
  std::unique_ptr<CholmodSupernodal> cholmod_super;
  std::unique_ptr<SupernodalSolver> supernodal;  // solves on cholmod_super's factor
  std::unique_ptr<Eigen::CholmodSimplicialLLT<Matrix, Eigen::Lower>> cholmod_simplicial;
#endif
};

SparseCholesky::SparseCholesky(const Matrix& K, const SparseCholeskyOptions& options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  CholeskyBackend b = options.backend;
#ifdef SLIM_HAVE_CHOLMOD
  if (b == CholeskyBackend::Auto) b = CholeskyBackend::Cholmod;
  const BlasThreadsScope blas(options.blas_threads);
  const SerialOpenMPScope serial;
  if (b == CholeskyBackend::Cholmod) {
    m.cholmod_super = factor_with_metis<CholmodSupernodal>(K);
    m.backend = "CHOLMOD supernodal";
    SupernodalFactor view;
    if (options.own_supernodal_solve && m.cholmod_super->view(view)) m.supernodal = std::make_unique<SupernodalSolver>(view);
  } else if (b == CholeskyBackend::CholmodSimplicial) {
    m.cholmod_simplicial = factor_with_metis<Eigen::CholmodSimplicialLLT<Matrix, Eigen::Lower>>(K);
    m.backend = "CHOLMOD simplicial";
  }
#else
  if (b == CholeskyBackend::Auto) b = CholeskyBackend::EigenLDLT;
  if (b != CholeskyBackend::EigenLDLT)
    throw std::invalid_argument("ArapSolver: CHOLMOD was not built in; use Backend::EigenLDLT or Auto");
#endif
  if (b == CholeskyBackend::EigenLDLT) {
    m.ldlt = factor_with<Eigen::SimplicialLDLT<Matrix, Eigen::Lower>>(K);
    m.backend = "Eigen SimplicialLDLT";
  }
}

SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

bool SparseCholesky::solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& x) const {
  const Impl& m = *impl_;
  bool ok = true;
#ifdef SLIM_HAVE_CHOLMOD
  if (m.supernodal) {
    x = m.supernodal->solve(rhs);  // no BLAS
  } else if (m.cholmod_super) {
    const BlasThreadsScope blas(m.options.blas_threads);
    x = m.cholmod_super->solve(rhs);
    ok = m.cholmod_super->info() == Eigen::Success;
  } else if (m.cholmod_simplicial) {
    x = m.cholmod_simplicial->solve(rhs);
    ok = m.cholmod_simplicial->info() == Eigen::Success;
  }
#endif
  if (m.ldlt) x = m.ldlt->solve(rhs);
  return ok && x.allFinite();
}

const std::string& SparseCholesky::backend_name() const { return impl_->backend; }

bool SparseCholesky::cholmod_available() {
#ifdef SLIM_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

}  // namespace slim
