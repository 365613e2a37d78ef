#include "core/step_guards.h"

#include <algorithm>

#include "core/arap.h"

namespace slim {

namespace {

// The local guard's rounds of rolling vertices back before it gives up (on the test shapes it
// needs at most 9).
constexpr int kMaxRollBackRounds = 64;

bool is_inverted(const Points& P, const Tets& T, int t) { return edge_matrix(P, T.row(t)).determinant() <= 0.0; }

int inverted_among(const Points& P, const Tets& T, const std::vector<int>& tets) {
  int count = 0;
  const int n = static_cast<int>(tets.size());
#pragma omp parallel for schedule(static) reduction(+ : count) if (n > 4096)
  for (int i = 0; i < n; ++i) count += is_inverted(P, T, tets[static_cast<size_t>(i)]);
  return count;
}

// The largest fraction f of `step` (halvings of [0, 1]) at which none of `tets` is inverted.
double largest_fraction(const Points& current, const Points& step, const Tets& T, const std::vector<int>& tets) {
  double lo = 0.0, hi = 1.0;
  for (int b = 0; b < 20; ++b) {
    const double mid = 0.5 * (lo + hi);
    (inverted_among(current + mid * step, T, tets) == 0 ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

bool keep_above_plate(Points& proposed, const Eigen::Vector3d& d, double plate) {
  bool moved = false;
  for (Eigen::Index v = 0; v < proposed.rows(); ++v) {
    const double below = plate - proposed.row(v).dot(d.transpose());
    if (below > 0.0) {
      proposed.row(v) += below * d.transpose();
      moved = true;
    }
  }
  return moved;
}

BudgetGuard keep_within_budget(const Points& rest, const Points& current, Points& proposed, double budget,
                               const std::vector<bool>& together) {
  std::vector<Eigen::Index> over;
  bool touches_together = false;
  for (Eigen::Index v = 0; v < proposed.rows(); ++v)
    if ((proposed.row(v) - rest.row(v)).norm() > budget) {
      over.push_back(v);
      touches_together = touches_together || together[static_cast<size_t>(v)];
    }
  if (over.empty()) return BudgetGuard::Within;
  if (!touches_together) {
    for (Eigen::Index v : over) {
      const Eigen::RowVector3d offset = proposed.row(v) - rest.row(v);
      proposed.row(v) = rest.row(v) + offset * (budget / offset.norm());
    }
    return BudgetGuard::Projected;
  }
  const Points step = proposed - current;
  double lo = 0.0, hi = 1.0;
  for (int b = 0; b < 30; ++b) {
    const double mid = 0.5 * (lo + hi);
    const Points trial = current + mid * step;
    ((trial - rest).rowwise().norm().maxCoeff() <= budget ? lo : hi) = mid;
  }
  proposed = current + lo * step;
  return BudgetGuard::CutBack;
}

std::vector<int> inverted_tets(const Points& P, const Tets& T) {
  const int nt = static_cast<int>(T.rows());
  std::vector<char> bad(static_cast<size_t>(nt));
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) bad[static_cast<size_t>(t)] = is_inverted(P, T, t);
  std::vector<int> list;
  for (int t = 0; t < nt; ++t)
    if (bad[static_cast<size_t>(t)]) list.push_back(t);
  return list;
}

bool roll_back_inverting(const Points& current, Points& proposed, const Tets& T, const std::vector<bool>& together,
                         std::vector<int> inverting, int& held_back) {
  Points trial = proposed;
  std::vector<char> back(static_cast<size_t>(current.rows()), 0);
  for (int round = 0; round < kMaxRollBackRounds && !inverting.empty(); ++round) {
    for (int t : inverting)
      for (int k = 0; k < 4; ++k) {
        const int v = T(t, k);
        if (together[static_cast<size_t>(v)]) return false;
        trial.row(v) = current.row(v);
        back[static_cast<size_t>(v)] = 1;
      }
    inverting = inverted_tets(trial, T);
  }
  if (!inverting.empty()) return false;
  proposed = std::move(trial);
  held_back = static_cast<int>(std::count(back.begin(), back.end(), 1));
  return true;
}

void cut_back_to_valid(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& probe) {
  const Points step = proposed - current;
  double lo = largest_fraction(current, step, T, probe);
  if (lo > 0.0 && !inverted_tets(current + lo * step, T).empty()) {
    std::vector<int> all(static_cast<size_t>(T.rows()));
    for (int t = 0; t < static_cast<int>(T.rows()); ++t) all[static_cast<size_t>(t)] = t;
    lo = largest_fraction(current, step, T, all);
  }
  proposed = current + lo * step;
}

}  // namespace slim
