// The back-substitution on CHOLMOD's supernodal factor: CHOLMOD's own solve is the oracle, the
// residual is checked independently, the two halves of the sweeps must not change the bits, and
// views that are not postordered supernodal factors are refused.
#include <gtest/gtest.h>

#ifdef SLIM_HAVE_CHOLMOD

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/solver/supernodal_solve.h"

using namespace slim;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

namespace {

// The graph Laplacian of an nx x ny x nz grid (6 neighbours, weights 1..4 varying by edge) plus
// `shift` on the diagonal: symmetric positive definite, 3D fill like the optimizer's domains.
// Stored as its lower triangle, as the global step stores K.
SparseMatrix grid_matrix(int nx, int ny, int nz, double shift = 0.05) {
  auto id = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  const int n = nx * ny * nz;
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, shift);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = id(i, j, k);
        const int next[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& q : next) {
          if (q[0] >= nx || q[1] >= ny || q[2] >= nz) continue;
          const int b = id(q[0], q[1], q[2]);
          const double w = 1.0 + (a + 3 * b) % 4;
          t.emplace_back(std::max(a, b), std::min(a, b), -w);
          diag(a) += w;
          diag(b) += w;
        }
      }
  for (int a = 0; a < n; ++a) t.emplace_back(a, a, diag(a));
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

// Two matrices side by side with nothing coupling them: an elimination forest with two roots.
SparseMatrix block_diagonal(const SparseMatrix& A, const SparseMatrix& B) {
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  const int off = static_cast<int>(A.rows());
  for (int c = 0; c < B.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(B, c); it; ++it) t.emplace_back(off + it.row(), off + it.col(), it.value());
  SparseMatrix K(A.rows() + B.rows(), A.cols() + B.cols());
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

class Factor : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  explicit Factor(const SparseMatrix& K) {
    compute(K);
    if (info() != Eigen::Success) throw std::runtime_error("CHOLMOD failed on the test matrix");
  }
  SupernodalFactor view() const {
    SupernodalFactor f;
    if (!supernodal_view(m_cholmodFactor, f)) throw std::runtime_error("not a supernodal LL^T");
    return f;
  }
};

Eigen::MatrixXd random_rhs(int n, unsigned seed, int columns = 3) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd b(n, columns);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < columns; ++c) b(i, c) = u(gen);
  return b;
}

// Both builds of the kernels (AVX2 + FMA where the CPU has them, and the baseline), in 4 lanes
// (1 and 3 right-hand sides) and in 8 (6 and 8).
void expect_solves(const SparseMatrix& K, unsigned seed) {
  const Factor factor(K);
  for (int columns : {1, 3, 6, 8}) {
    const Eigen::MatrixXd b = random_rhs(static_cast<int>(K.rows()), seed, columns);
    const Eigen::MatrixXd oracle = factor.solve(b);
    for (SupernodalKernels kernels : {SupernodalKernels::Auto, SupernodalKernels::Baseline}) {
      const SupernodalSolver solver(factor.view(), kernels);
      const Eigen::MatrixXd x = solver.solve(b);
      ASSERT_EQ(x.cols(), columns);
      EXPECT_LE((x - oracle).norm(), 1e-12 * oracle.norm()) << K.rows() << " " << columns << " " << solver.kernels();
      const Eigen::MatrixXd residual = K.selfadjointView<Eigen::Lower>() * x - b;
      EXPECT_LE(residual.norm(), 1e-11 * b.norm()) << K.rows() << " " << columns << " " << solver.kernels();
    }
  }
}

}  // namespace

TEST(SupernodalSolve, MatchesCholmodOnGridMatrices) {
  expect_solves(grid_matrix(1, 1, 1), 1);   // one unknown
  expect_solves(grid_matrix(3, 2, 2), 2);   // a handful: a supernode narrower than a panel
  expect_solves(grid_matrix(9, 8, 7), 3);   // panels of eight and their remainders
  expect_solves(grid_matrix(26, 24, 22), 4);  // large enough for the two halves on two threads
}

TEST(SupernodalSolve, ForestOfIndependentBlocks) {
  expect_solves(block_diagonal(grid_matrix(20, 18, 16), grid_matrix(17, 19, 15, 0.3)), 5);
  // Two roots of equal weight: one half each, nothing shared above them.
  const Factor factor(block_diagonal(grid_matrix(20, 18, 16), grid_matrix(20, 18, 16, 0.3)));
  const SupernodalSolver solver(factor.view());
  EXPECT_GT(solver.half_work(0), 0.0);
  EXPECT_GT(solver.half_work(1), 0.0);
  EXPECT_EQ(solver.shared_work(), 0.0);
}

TEST(SupernodalSolve, SplitsTheTreeIntoBalancedHalves) {
  const Factor factor(grid_matrix(26, 24, 22));
  const SupernodalSolver solver(factor.view());
  const double a = solver.half_work(0), b = solver.half_work(1), shared = solver.shared_work();
  EXPECT_GT(std::min(a, b), 0.5 * std::max(a, b)) << a << " " << b;
  EXPECT_LT(shared, a + b) << "the part both halves wait for should be the smaller one";
}

TEST(SupernodalSolve, AutoTakesTheAvx2KernelsWhereTheCpuHasThem) {
  const Factor factor(grid_matrix(3, 3, 3));
#if defined(__x86_64__)
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  const bool avx2 = false;
#endif
  EXPECT_STREQ(SupernodalSolver(factor.view()).kernels(), avx2 ? "AVX2" : "baseline");
  EXPECT_STREQ(SupernodalSolver(factor.view(), SupernodalKernels::Baseline).kernels(), "baseline");
}

#ifdef _OPENMP
TEST(SupernodalSolve, SameBitsOnOneAndTwoThreads) {
  const Factor factor(grid_matrix(26, 24, 22));
  const Eigen::MatrixXd b = random_rhs(static_cast<int>(factor.rows()), 6);
  for (SupernodalKernels kernels : {SupernodalKernels::Auto, SupernodalKernels::Baseline}) {
    const SupernodalSolver solver(factor.view(), kernels);
    const int before = omp_get_max_threads();
    omp_set_num_threads(1);
    const Eigen::MatrixXd one = solver.solve(b);
    omp_set_num_threads(2);
    const Eigen::MatrixXd two = solver.solve(b);
    const Eigen::MatrixXd again = solver.solve(b);
    omp_set_num_threads(before);
    EXPECT_TRUE(one == two) << solver.kernels();
    EXPECT_TRUE(two == again) << solver.kernels();
  }
}
#endif

TEST(SupernodalSolve, RefusesViewsThatAreNotPostorderedSupernodalFactors) {
  const Factor factor(grid_matrix(6, 5, 4));
  const SupernodalFactor good = factor.view();
  ASSERT_NO_THROW(SupernodalSolver{good});
  ASSERT_GT(good.supernodes, 2);

  std::vector<int> permutation(good.permutation, good.permutation + good.n);
  permutation[1] = permutation[0];
  SupernodalFactor repeated = good;
  repeated.permutation = permutation.data();
  EXPECT_THROW(SupernodalSolver{repeated}, std::invalid_argument);

  // The first supernode with rows below its columns, those rows in descending order.
  std::vector<int> rows(good.rows, good.rows + good.row_start[good.supernodes]);
  int s = 0;
  while (good.row_start[s + 1] - good.row_start[s] - (good.first_column[s + 1] - good.first_column[s]) < 2) ++s;
  const int below = good.row_start[s] + good.first_column[s + 1] - good.first_column[s];
  std::reverse(rows.begin() + below, rows.begin() + good.row_start[s + 1]);
  SupernodalFactor unsorted = good;
  unsorted.rows = rows.data();
  EXPECT_THROW(SupernodalSolver{unsorted}, std::invalid_argument);

  SupernodalFactor missing = good;
  missing.values = nullptr;
  EXPECT_THROW(SupernodalSolver{missing}, std::invalid_argument);

  SupernodalFactor uncovered = good;
  uncovered.n = good.n + 1;
  EXPECT_THROW(SupernodalSolver{uncovered}, std::invalid_argument);
}

// The global step solves its three columns and a load's three in one sweep (arap.h): each lane
// does the same arithmetic in the same order whatever the lane count, so the bits match.
TEST(SupernodalSolve, SixColumnsTogetherGiveTheBitsOfEachThreeAlone) {
  const Factor factor(grid_matrix(26, 24, 22));
  const Eigen::MatrixXd b = random_rhs(static_cast<int>(factor.rows()), 7, 6);
  for (SupernodalKernels kernels : {SupernodalKernels::Auto, SupernodalKernels::Baseline}) {
    const SupernodalSolver solver(factor.view(), kernels);
    const Eigen::MatrixXd both = solver.solve(b);
    EXPECT_TRUE(both.leftCols(3) == solver.solve(b.leftCols(3))) << solver.kernels();
    EXPECT_TRUE(both.rightCols(3) == solver.solve(b.rightCols(3))) << solver.kernels();
  }
}

TEST(SupernodalSolve, RightHandSideMustBeNByOneToEight) {
  const Factor factor(grid_matrix(3, 3, 3));
  const SupernodalSolver solver(factor.view());
  EXPECT_THROW(solver.solve(Eigen::MatrixXd::Zero(27, 0)), std::invalid_argument);
  EXPECT_THROW(solver.solve(Eigen::MatrixXd::Zero(27, 9)), std::invalid_argument);
  EXPECT_THROW(solver.solve(Eigen::MatrixXd::Zero(26, 3)), std::invalid_argument);
}

#endif  // SLIM_HAVE_CHOLMOD (without it the global step uses Eigen's solver and this file is empty)
