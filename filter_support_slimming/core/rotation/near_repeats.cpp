#include "core/rotation/near_repeats.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace slim {
namespace {

// Below this many columns a plain pass over the kept ones is the cheapest.
constexpr Eigen::Index kPlainPass = 32;

using Cell = std::array<std::int64_t, 3>;
struct CellHash {
  size_t operator()(const Cell& c) const {
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };  // wraps, never overflows
    return static_cast<size_t>(u(c[0]) * 73856093u ^ u(c[1]) * 19349663u ^ u(c[2]) * 83492791u);
  }
};

}  // namespace

// The kept columns in cells of a grid at least as wide as the tolerance: a column within the
// tolerance of another lies in its cell or a neighbouring one. Only kept columns enter the grid,
// so a thousand copies of one normal cost one comparison each, not a window of a thousand. Each
// cell lists its columns in increasing order, so the first within the tolerance is its least.
std::vector<Eigen::Index> near_repeats(const Eigen::Matrix3Xd& unit, double tol) {
  const Eigen::Index n = unit.cols();
  std::vector<Eigen::Index> kept(static_cast<size_t>(n));
  auto within = [&](Eigen::Index j, Eigen::Index i) { return (unit.col(j) - unit.col(i)).squaredNorm() <= tol * tol; };
  if (n <= kPlainPass) {
    std::vector<Eigen::Index> firsts;
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Index& mine = kept[static_cast<size_t>(i)];
      mine = i;
      for (Eigen::Index j : firsts)
        if (within(j, i)) {
          mine = j;
          break;
        }
      if (mine == i) firsts.push_back(i);
    }
    return kept;
  }
  const double h = std::max(tol, 1e-9);
  std::unordered_map<Cell, std::vector<Eigen::Index>, CellHash> cells;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index& mine = kept[static_cast<size_t>(i)];
    mine = i;
    const Eigen::Vector3d scaled = unit.col(i) / h;
    if (!(scaled.cwiseAbs().maxCoeff() < 1e15)) continue;  // not finite, or far beyond a unit vector: alone
    const Cell c{static_cast<std::int64_t>(std::floor(scaled.x())), static_cast<std::int64_t>(std::floor(scaled.y())),
                 static_cast<std::int64_t>(std::floor(scaled.z()))};
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
          if (found == cells.end()) continue;
          for (Eigen::Index j : found->second) {
            if (j >= mine) break;
            if (within(j, i)) {
              mine = j;
              break;
            }
          }
        }
    if (mine == i) cells[c].push_back(i);
  }
  return kept;
}

}  // namespace slim
