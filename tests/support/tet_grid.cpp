#include "support/tet_grid.h"

#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

namespace slim::test {

TetMesh tet_grid(int nx, int ny, int nz, double h, const Eigen::Vector3d& origin) {
  if (nx <= 0 || ny <= 0 || nz <= 0 || !(h > 0.0))
    throw std::invalid_argument("tet_grid: cube counts and side must be positive");
  const int sx = nx + 1, sy = ny + 1, sz = nz + 1;
  auto id = [&](int i, int j, int k) { return i + sx * (j + sy * k); };

  TetMesh m;
  m.V.resize(sx * sy * sz, 3);
  for (int k = 0; k < sz; ++k)
    for (int j = 0; j < sy; ++j)
      for (int i = 0; i < sx; ++i)
        m.V.row(id(i, j, k)) = (origin + h * Eigen::Vector3d(i, j, k)).transpose();

  // Kuhn split: one tet per axis order (a, b, c), walking 000 -> +a -> +b -> +c = 111. An odd
  // permutation of the axes gives a negative volume, so its last two vertices are swapped.
  const std::array<std::array<int, 3>, 6> orders = {
      {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};
  m.T.resize(6 * nx * ny * nz, 4);
  int t = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int o = 0; o < 6; ++o) {
          std::array<int, 3> c = {i, j, k};
          std::array<int, 4> v;
          v[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[orders[o][s]];
            v[s + 1] = id(c[0], c[1], c[2]);
          }
          if (o >= 3) std::swap(v[2], v[3]);
          m.T.row(t++) << v[0], v[1], v[2], v[3];
        }
  return m;
}

std::vector<int> grid_bottom_vertices(int nx, int ny) {
  std::vector<int> out;
  out.reserve(static_cast<size_t>((nx + 1) * (ny + 1)));
  for (int i = 0; i < (nx + 1) * (ny + 1); ++i) out.push_back(i);
  return out;
}

}  // namespace slim::test
