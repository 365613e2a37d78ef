#include "core/optimizer/costly_overhangs.h"

#include <algorithm>
#include <numeric>

#include "core/print/face_columns.h"

namespace slim {

std::vector<bool> costly_overhangs(const Surface& input, const OverhangReport& before, const Eigen::Vector3d& d,
                                   double share) {
  if (share >= 1.0) return before.risky;
  const Eigen::VectorXd column = column_heights(input, d, before.risky);
  const Points n = face_normals(input);
  const Eigen::VectorXd area = face_areas(input);
  std::vector<int> ranked;
  std::vector<double> cost(before.risky.size(), 0.0);
  double total = 0.0;
  for (size_t f = 0; f < before.risky.size(); ++f) {
    if (!before.risky[f]) continue;
    const auto i = static_cast<Eigen::Index>(f);
    cost[f] = face_shadow(area(i), n.row(i).dot(d), column(i));
    total += cost[f];
    ranked.push_back(static_cast<int>(f));
  }
  std::stable_sort(ranked.begin(), ranked.end(), [&](int a, int b) { return cost[static_cast<size_t>(a)] > cost[static_cast<size_t>(b)]; });
  std::vector<bool> costly(before.risky.size(), false);
  double kept = 0.0;
  for (const int f : ranked) {
    if (!(kept < share * total)) break;
    costly[static_cast<size_t>(f)] = true;
    kept += cost[static_cast<size_t>(f)];
  }
  return costly;
}

}  // namespace slim
