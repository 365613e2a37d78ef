// The global step's back-substitution (arap.h) on a supernodal Cholesky factor L L^T = P K P^T,
// for the three right-hand sides x, y, z at once (or up to eight: the global step and a load's
// response together, arap.h).
//
// Why not the factoring library's own solve: CHOLMOD solves supernode by supernode through BLAS
// calls sized for many right-hand sides; with three, the calls' overhead and narrow kernels
// dominate (docs/history/speed-earlier.md). Here each supernode's dense block is streamed
// once per sweep, eight columns at a time against the three right-hand sides held in one 4-wide
// register (up to eight right-hand sides in 8 lanes cost little more, the
// sweep being bound by reading the factor), and the two sweeps run on two threads where the elimination tree
// splits into independent subtrees.
//
// Input: a view of the factor in CHOLMOD's supernodal layout (cholmod_core.h, "supernodal"):
//   n             unknowns;
//   supernodes    number of supernodes, numbered so that every supernode comes after all of its
//                 descendants in the elimination tree (CHOLMOD's postordered factor);
//   first_column  supernodes + 1: supernode s holds the columns [first_column[s], first_column[s+1]);
//   row_start     supernodes + 1: its row indices are rows[row_start[s] .. row_start[s+1]), its
//                 own columns first, then the rows below them in ascending order;
//   value_start   supernodes: its values are a dense column-major block of (#rows) x (#columns)
//                 at values + value_start[s], the upper triangle of the diagonal block unused;
//   permutation   n: row k of P K P^T is row permutation[k] of K.
// The view borrows the arrays; they must outlive the solver.
//
// solve(rhs): rhs #n by k, 1 <= k <= 8 (any units) -> K^-1 rhs, #n by k. Deterministic: the schedule (which
// subtrees form the two halves) depends on the factor alone, and the halves' contributions to
// their common ancestors are added in a fixed order, so the bits do not depend on the thread
// count (a run with one thread does both halves in turn). The kernels are built for the baseline
// and for AVX2 + FMA; a machine always runs the same one, and the two may differ in the last bits.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

namespace slim {

struct SupernodalFactor {
  int n = 0;
  int supernodes = 0;
  const int* first_column = nullptr;
  const int* row_start = nullptr;
  const int* value_start = nullptr;
  const int* rows = nullptr;
  const double* values = nullptr;
  const int* permutation = nullptr;
};

#ifdef SLIM_HAVE_CHOLMOD
// The view of a CHOLMOD factor, when it is a real, double, int-indexed supernodal LL^T (what
// CholmodSupernodalLLT asks for); false otherwise (CHOLMOD's own solve must then be used).
bool supernodal_view(const struct cholmod_factor_struct* L, SupernodalFactor& out);
#endif

// Which build of the sweep kernels runs: Auto takes the AVX2 + FMA one on x86-64 CPUs that have
// both, else the baseline; Baseline always takes the baseline (for tests and comparisons).
enum class SupernodalKernels { Auto, Baseline };

class SupernodalSolver {
 public:
  // Checks the view's structure (throws std::invalid_argument when it is not a postordered
  // supernodal factor), plans the two halves of the sweeps and picks the kernels.
  explicit SupernodalSolver(const SupernodalFactor& factor, SupernodalKernels kernels = SupernodalKernels::Auto);
  ~SupernodalSolver();
  SupernodalSolver(SupernodalSolver&&) noexcept;
  SupernodalSolver& operator=(SupernodalSolver&&) noexcept;

  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const;

  // How the work was split, for tests and benchmarks: entries of L (stored block sizes) in each
  // half and in the common ancestors done after (forward) or before (backward) the halves.
  double half_work(int half) const;
  double shared_work() const;
  const char* kernels() const;  // "AVX2" or "baseline"

 private:
  struct Plan;
  template <int N>
  Eigen::MatrixXd solve_lanes(const Eigen::MatrixXd& rhs) const;  // N = 4 or 8 lanes
  SupernodalFactor f_;
  std::unique_ptr<Plan> plan_;
};

}  // namespace slim
