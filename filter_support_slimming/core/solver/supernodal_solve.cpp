#include "core/solver/supernodal_solve.h"
#include "core/solver/supernodal_sweeps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

#ifdef SLIM_HAVE_CHOLMOD
#include <cholmod.h>

#include <limits>
#endif

namespace slim {

namespace {

// Below this many stored entries of L the two halves run on the calling thread (a thread team
// costs more than the sweep); the bits are the same either way.
constexpr double kParallelWork = 1 << 18;

// The sweeps over a list of supernodes (supernodal_sweeps.h), for 4 and 8 lanes, built twice on
// x86-64: for the baseline (SSE2) and for AVX2 with FMA, the kernels inlined into each. Which one
// runs is chosen once per solver (SupernodalKernels), so a machine always gives the same bits;
// two machines of different generations may differ in the last bits.
#define SLIM_DEFINE_SWEEPS(SUFFIX, N, TARGET)                                                                  \
  TARGET void forward_range##SUFFIX(const SupernodalFactor& f, int first, int last, double* X, double* W,      \
                                    const int* shared_slot, double* shared) {                                  \
    for (int s = first; s <= last; ++s) sweeps::forward_supernode<N>(f, s, X, W, shared_slot, shared);         \
  }                                                                                                            \
  TARGET void backward_range##SUFFIX(const SupernodalFactor& f, int first, int last, double* X, double* W) {    \
    for (int s = last; s >= first; --s) sweeps::backward_supernode<N>(f, s, X, W);                             \
  }
SLIM_DEFINE_SWEEPS(4_baseline, 4, )
SLIM_DEFINE_SWEEPS(8_baseline, 8, )
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define SLIM_HAVE_AVX2_KERNELS 1
SLIM_DEFINE_SWEEPS(4_avx2, 4, __attribute__((target("avx2,fma"))))
SLIM_DEFINE_SWEEPS(8_avx2, 8, __attribute__((target("avx2,fma"))))
#endif
#undef SLIM_DEFINE_SWEEPS

[[noreturn]] void bad_factor(const std::string& why) {
  throw std::invalid_argument("SupernodalSolver: the factor is not a postordered supernodal one (" + why + ")");
}

}  // namespace

#ifdef SLIM_HAVE_CHOLMOD
bool supernodal_view(const cholmod_factor* L, SupernodalFactor& out) {
  if (!L || !L->is_super || !L->is_ll || L->itype != CHOLMOD_INT || L->xtype != CHOLMOD_REAL ||
      L->dtype != CHOLMOD_DOUBLE || L->n > static_cast<size_t>(std::numeric_limits<int>::max()))
    return false;
  out.n = static_cast<int>(L->n);
  out.supernodes = static_cast<int>(L->nsuper);
  out.first_column = static_cast<const int*>(L->super);
  out.row_start = static_cast<const int*>(L->pi);
  out.value_start = static_cast<const int*>(L->px);
  out.rows = static_cast<const int*>(L->s);
  out.values = static_cast<const double*>(L->x);
  out.permutation = static_cast<const int*>(L->Perm);
  return true;
}
#endif

struct SupernodalSolver::Plan {
  std::vector<int> shared;                            // supernodes above both halves, ascending
  std::vector<std::pair<int, int>> halves[2];         // subtrees as supernode ranges [first, last]
  std::vector<int> shared_slot;                       // n: a shared supernode's column -> slot, else -1
  int shared_columns = 0;
  int max_rows = 0;
  double work[2] = {0.0, 0.0}, shared_work = 0.0;
  using Forward = void (*)(const SupernodalFactor&, int, int, double*, double*, const int*, double*);
  using Backward = void (*)(const SupernodalFactor&, int, int, double*, double*);
  // The sweeps for 4 lanes ([0]: up to four right-hand sides) and for 8 ([1]: up to eight).
  Forward forward[2] = {forward_range4_baseline, forward_range8_baseline};
  Backward backward[2] = {backward_range4_baseline, backward_range8_baseline};
};

namespace {

// The supernodal elimination tree, checked to be in postorder: a supernode's parent owns its first
// row below its columns, and a subtree is the contiguous range [first, root].
struct EliminationTree {
  std::vector<double> work, subtree;  // stored entries of each supernode, and of its subtree
  std::vector<int> first;             // the first supernode of each subtree
  std::vector<std::vector<int>> children;
  std::vector<int> roots;
  int max_rows = 0;
};

// Checks the view's structure and builds the tree (throws std::invalid_argument).
EliminationTree elimination_tree(const SupernodalFactor& f) {
  const int n = f.n, ns = f.supernodes;
  if (n < 0 || ns < 0 || (ns > 0 && (!f.first_column || !f.row_start || !f.value_start || !f.rows || !f.values)) ||
      (n > 0 && !f.permutation))
    bad_factor("missing arrays");
  if (ns == 0 ? n != 0 : (f.first_column[0] != 0 || f.first_column[ns] != n || f.row_start[0] != 0))
    bad_factor("the supernodes do not cover the columns");
  EliminationTree tree;
  std::vector<int> column_owner(static_cast<size_t>(n));
  tree.work.resize(static_cast<size_t>(ns));
  for (int s = 0; s < ns; ++s) {
    const int c0 = f.first_column[s], nc = f.first_column[s + 1] - c0, nr = f.row_start[s + 1] - f.row_start[s];
    if (nc <= 0 || nr < nc) bad_factor("supernode " + std::to_string(s) + " has no columns or too few rows");
    const int* rows = f.rows + f.row_start[s];
    for (int i = 0; i < nr; ++i)
      if (i < nc ? rows[i] != c0 + i : (rows[i] <= rows[i - 1] || rows[i] >= n))
        bad_factor("supernode " + std::to_string(s) + " has rows out of order");
    for (int c = c0; c < c0 + nc; ++c) column_owner[static_cast<size_t>(c)] = s;
    tree.work[static_cast<size_t>(s)] = static_cast<double>(nc) * nr;
    tree.max_rows = std::max(tree.max_rows, nr);
  }
  std::vector<int> seen(static_cast<size_t>(n), 0);
  for (int k = 0; k < n; ++k) {
    const int r = f.permutation[k];
    if (r < 0 || r >= n || seen[static_cast<size_t>(r)]++) bad_factor("the permutation repeats or leaves a row");
  }
  tree.subtree = tree.work;
  tree.first.resize(static_cast<size_t>(ns));
  tree.children.resize(static_cast<size_t>(ns));
  for (int s = 0; s < ns; ++s) {
    const int nc = f.first_column[s + 1] - f.first_column[s], nr = f.row_start[s + 1] - f.row_start[s];
    const std::vector<int>& kids = tree.children[static_cast<size_t>(s)];
    tree.first[static_cast<size_t>(s)] = kids.empty() ? s : tree.first[static_cast<size_t>(kids.front())];
    if (nr == nc) {
      tree.roots.push_back(s);
      continue;
    }
    const int up = column_owner[static_cast<size_t>(f.rows[f.row_start[s] + nc])];
    if (up <= s) bad_factor("supernode " + std::to_string(s) + " comes after its parent");
    tree.subtree[static_cast<size_t>(up)] += tree.subtree[static_cast<size_t>(s)];
    tree.children[static_cast<size_t>(up)].push_back(s);
  }
  for (int s = 0; s < ns; ++s) {
    const std::vector<int>& kids = tree.children[static_cast<size_t>(s)];
    for (size_t c = 0; c < kids.size(); ++c)
      if (c + 1 == kids.size() ? kids[c] != s - 1 : tree.first[static_cast<size_t>(kids[c + 1])] != kids[c] + 1)
        bad_factor("the supernodes are not in postorder");
  }
  return tree;
}

// Deals the subtrees to the lighter half, heaviest first; returns the heavier half's load.
double deal(const EliminationTree& tree, std::vector<int> subtrees, std::vector<std::pair<int, int>> (&halves)[2],
            double (&load)[2]) {
  std::sort(subtrees.begin(), subtrees.end(), [&](int a, int b) {
    return tree.subtree[static_cast<size_t>(a)] != tree.subtree[static_cast<size_t>(b)]
               ? tree.subtree[static_cast<size_t>(a)] > tree.subtree[static_cast<size_t>(b)]
               : a < b;
  });
  for (int h = 0; h < 2; ++h) {
    halves[h].clear();
    load[h] = 0.0;
  }
  for (int c : subtrees) {
    const int h = load[1] < load[0] ? 1 : 0;
    halves[h].emplace_back(tree.first[static_cast<size_t>(c)], c);
    load[h] += tree.subtree[static_cast<size_t>(c)];
  }
  return std::max(load[0], load[1]);
}

struct Halves {
  std::vector<int> shared;                   // supernodes done after (forward) or before the halves
  std::vector<std::pair<int, int>> halves[2];  // subtree ranges [first, root]
  double work[2] = {0.0, 0.0}, shared_work = 0.0;
};

// Which subtrees make the two halves: the candidates start as the roots, and the heaviest one is
// split again and again (its root goes to the shared part, done after the halves, its children
// become candidates). Each state deals the candidates to the lighter half, heaviest first, and the
// state with the shortest estimated time, shared + heavier half, is kept.
Halves plan_halves(const EliminationTree& tree) {
  Halves p;
  std::vector<int> candidates = tree.roots, shared;
  double shared_work = 0.0, best_time = HUGE_VAL;
  constexpr int kMaxSplits = 64;  // the shared part only grows: a good split is an early one
  for (int split = 0; split <= kMaxSplits; ++split) {
    std::vector<std::pair<int, int>> halves[2];
    double load[2];
    const double time = shared_work + deal(tree, candidates, halves, load);
    if (time < best_time) {
      best_time = time;
      p.shared = shared;
      p.shared_work = shared_work;
      for (int h = 0; h < 2; ++h) {
        p.halves[h] = halves[h];
        p.work[h] = load[h];
      }
    }
    int heaviest = -1;
    for (int c : candidates)
      if (!tree.children[static_cast<size_t>(c)].empty() &&
          (heaviest < 0 || tree.subtree[static_cast<size_t>(c)] > tree.subtree[static_cast<size_t>(heaviest)]))
        heaviest = c;
    if (heaviest < 0) break;
    candidates.erase(std::find(candidates.begin(), candidates.end(), heaviest));
    shared.push_back(heaviest);
    shared_work += tree.work[static_cast<size_t>(heaviest)];
    const std::vector<int>& kids = tree.children[static_cast<size_t>(heaviest)];
    candidates.insert(candidates.end(), kids.begin(), kids.end());
  }
  std::sort(p.shared.begin(), p.shared.end());
  for (auto& h : p.halves) std::sort(h.begin(), h.end());
  return p;
}

}  // namespace

SupernodalSolver::SupernodalSolver(const SupernodalFactor& f, SupernodalKernels kernels)
    : f_(f), plan_(std::make_unique<Plan>()) {
  const EliminationTree tree = elimination_tree(f);
  Plan& p = *plan_;
  p.max_rows = tree.max_rows;
  Halves halves = plan_halves(tree);
  p.shared = std::move(halves.shared);
  p.shared_work = halves.shared_work;
  for (int h = 0; h < 2; ++h) {
    p.halves[h] = std::move(halves.halves[h]);
    p.work[h] = halves.work[h];
  }
#ifdef SLIM_HAVE_AVX2_KERNELS
  if (kernels == SupernodalKernels::Auto && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    p.forward[0] = forward_range4_avx2, p.forward[1] = forward_range8_avx2;
    p.backward[0] = backward_range4_avx2, p.backward[1] = backward_range8_avx2;
  }
#else
  (void)kernels;
#endif
  p.shared_slot.assign(static_cast<size_t>(f.n), -1);
  for (int s : p.shared)
    for (int c = f.first_column[s]; c < f.first_column[s + 1]; ++c) p.shared_slot[static_cast<size_t>(c)] = p.shared_columns++;
}

SupernodalSolver::~SupernodalSolver() = default;
SupernodalSolver::SupernodalSolver(SupernodalSolver&&) noexcept = default;
SupernodalSolver& SupernodalSolver::operator=(SupernodalSolver&&) noexcept = default;

double SupernodalSolver::half_work(int half) const { return plan_->work[half == 0 ? 0 : 1]; }
double SupernodalSolver::shared_work() const { return plan_->shared_work; }
const char* SupernodalSolver::kernels() const {
  return plan_->forward[0] == forward_range4_baseline ? "baseline" : "AVX2";
}

Eigen::MatrixXd SupernodalSolver::solve(const Eigen::MatrixXd& rhs) const {
  if (rhs.rows() != f_.n || rhs.cols() < 1 || rhs.cols() > 8)
    throw std::invalid_argument("SupernodalSolver: the right-hand side must be n by 1 to 8");
  return rhs.cols() <= 4 ? solve_lanes<4>(rhs) : solve_lanes<8>(rhs);
}

template <int N>
Eigen::MatrixXd SupernodalSolver::solve_lanes(const Eigen::MatrixXd& rhs) const {
  const SupernodalFactor& f = f_;
  const Plan& p = *plan_;
  const Plan::Forward forward = p.forward[N == 4 ? 0 : 1];
  const Plan::Backward backward = p.backward[N == 4 ? 0 : 1];
  const Eigen::Index columns = rhs.cols();
  std::vector<double> X(N * static_cast<size_t>(f.n), 0.0);
  for (int k = 0; k < f.n; ++k)
    for (Eigen::Index c = 0; c < columns; ++c) X[N * static_cast<size_t>(k) + static_cast<size_t>(c)] = rhs(f.permutation[k], c);
  const size_t workspace = N * static_cast<size_t>(p.max_rows);
  std::vector<double> W(2 * workspace), shared(2 * N * static_cast<size_t>(p.shared_columns), 0.0);
  const bool parallel = p.work[0] + p.work[1] >= kParallelWork;
#ifdef _OPENMP
  const int threads = std::min(2, omp_get_max_threads());
#endif

#pragma omp parallel for schedule(static, 1) num_threads(threads) if (parallel)
  for (int half = 0; half < 2; ++half) {
    double* w = W.data() + half * workspace;
    double* acc = shared.data() + half * N * static_cast<size_t>(p.shared_columns);
    for (const auto& [first, last] : p.halves[half]) forward(f, first, last, X.data(), w, p.shared_slot.data(), acc);
  }
  for (int half = 0; half < 2; ++half)  // the halves' updates to the shared columns, in order
    for (int s : p.shared)
      for (int c = f.first_column[s]; c < f.first_column[s + 1]; ++c) {
        const size_t slot = half * static_cast<size_t>(p.shared_columns) + static_cast<size_t>(p.shared_slot[static_cast<size_t>(c)]);
        sweeps::add_row<N>(X.data() + N * static_cast<size_t>(c), shared.data() + N * slot);
      }
  for (int s : p.shared) forward(f, s, s, X.data(), W.data(), nullptr, nullptr);

  for (auto s = p.shared.rbegin(); s != p.shared.rend(); ++s) backward(f, *s, *s, X.data(), W.data());
#pragma omp parallel for schedule(static, 1) num_threads(threads) if (parallel)
  for (int half = 0; half < 2; ++half) {
    double* w = W.data() + half * workspace;
    for (auto range = p.halves[half].rbegin(); range != p.halves[half].rend(); ++range)
      backward(f, range->first, range->second, X.data(), w);
  }

  Eigen::MatrixXd x(f.n, columns);
  for (int k = 0; k < f.n; ++k)
    for (Eigen::Index c = 0; c < columns; ++c) x(f.permutation[k], c) = X[N * static_cast<size_t>(k) + static_cast<size_t>(c)];
  return x;
}

}  // namespace slim
