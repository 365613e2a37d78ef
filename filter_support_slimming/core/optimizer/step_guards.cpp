#include "core/optimizer/step_guards.h"

#include <algorithm>

#include "core/solver/arap.h"

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
                               const std::vector<int>& group) {
  BudgetGuard outcome;
  std::vector<int> overshooting_groups;
  for (Eigen::Index v = 0; v < proposed.rows(); ++v) {
    const Eigen::RowVector3d offset = proposed.row(v) - rest.row(v);
    if (!(offset.norm() > budget)) continue;
    const int g = group[static_cast<size_t>(v)];
    if (g >= 0) {
      overshooting_groups.push_back(g);
      continue;
    }
    proposed.row(v) = rest.row(v) + offset * (budget / offset.norm());
    ++outcome.projected;
  }
  std::sort(overshooting_groups.begin(), overshooting_groups.end());
  overshooting_groups.erase(std::unique(overshooting_groups.begin(), overshooting_groups.end()), overshooting_groups.end());
  for (int g : overshooting_groups) {
    std::vector<Eigen::Index> members;
    for (Eigen::Index v = 0; v < proposed.rows(); ++v)
      if (group[static_cast<size_t>(v)] == g) members.push_back(v);
    auto fits = [&](double f) {
      for (Eigen::Index v : members)
        if ((current.row(v) + f * (proposed.row(v) - current.row(v)) - rest.row(v)).norm() > budget) return false;
      return true;
    };
    double lo = 0.0, hi = 1.0;
    for (int b = 0; b < 30; ++b) {
      const double mid = 0.5 * (lo + hi);
      (fits(mid) ? lo : hi) = mid;
    }
    for (Eigen::Index v : members) proposed.row(v) = current.row(v) + lo * (proposed.row(v) - current.row(v));
    ++outcome.groups_held;
  }
  return outcome;
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

bool roll_back_inverting(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& group,
                         std::vector<int> inverting, int& held_back) {
  return roll_back_until(current, proposed, T, group, std::move(inverting),
                         [&](const Points& P) { return inverted_tets(P, T); }, held_back);
}

bool roll_back_until(const Points& current, Points& proposed, const Tets& T, const std::vector<int>& group,
                     std::vector<int> inverting, const std::function<std::vector<int>(const Points&)>& faulty,
                     int& held_back) {
  Points trial = proposed;
  std::vector<char> back(static_cast<size_t>(current.rows()), 0);
  std::vector<char> group_back;
  auto hold = [&](Eigen::Index v) {
    trial.row(v) = current.row(v);
    back[static_cast<size_t>(v)] = 1;
  };
  for (int round = 0; round < kMaxRollBackRounds && !inverting.empty(); ++round) {
    for (int t : inverting)
      for (int k = 0; k < 4; ++k) {
        const int v = T(t, k), g = group[static_cast<size_t>(v)];
        if (g < 0) {
          hold(v);
          continue;
        }
        if (group_back.size() <= static_cast<size_t>(g)) group_back.resize(static_cast<size_t>(g) + 1, 0);
        if (group_back[static_cast<size_t>(g)]) continue;
        group_back[static_cast<size_t>(g)] = 1;  // the whole feature goes back, in one piece
        for (Eigen::Index u = 0; u < current.rows(); ++u)
          if (group[static_cast<size_t>(u)] == g) hold(u);
      }
    inverting = faulty(trial);
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
