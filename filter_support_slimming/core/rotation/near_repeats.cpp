#include "core/rotation/near_repeats.h"

#include <algorithm>

namespace slim {
std::vector<Eigen::Index> near_repeats(const Eigen::Matrix3Xd& unit, double tol) {
  const Eigen::Index n = unit.cols();
  // Sorted by x, the columns within the tolerance of one lie in a window around it.
  std::vector<Eigen::Index> by_x(static_cast<size_t>(n)), where(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) by_x[static_cast<size_t>(i)] = i;
  std::sort(by_x.begin(), by_x.end(), [&](Eigen::Index a, Eigen::Index b) {
    return unit(0, a) < unit(0, b) || (unit(0, a) == unit(0, b) && a < b);
  });
  for (size_t k = 0; k < by_x.size(); ++k) where[static_cast<size_t>(by_x[k])] = static_cast<Eigen::Index>(k);
  std::vector<Eigen::Index> kept(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {  // in column order: the kept columns before i are final
    Eigen::Index& mine = kept[static_cast<size_t>(i)];
    mine = i;
    auto consider = [&](size_t k) {
      const Eigen::Index j = by_x[k];
      if (j < i && j < mine && kept[static_cast<size_t>(j)] == j && (unit.col(j) - unit.col(i)).squaredNorm() <= tol * tol) mine = j;
    };
    const double x = unit(0, i);
    const size_t at = static_cast<size_t>(where[static_cast<size_t>(i)]);
    for (size_t k = at; k-- > 0 && unit(0, by_x[k]) >= x - tol;) consider(k);
    for (size_t k = at + 1; k < by_x.size() && unit(0, by_x[k]) <= x + tol; ++k) consider(k);
  }
  return kept;
}

}  // namespace slim
