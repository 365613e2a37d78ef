#include "core/face_adjacency.h"

#include <array>

namespace slim {

FaceAdjacency face_adjacency(const Surface& s) {
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  // The faces row by row: the searches below jump between faces, and F is stored by column.
  std::vector<std::array<int, 3>> tri(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) tri[f] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
  FaceAdjacency a;
  a.vertex_begin.assign(static_cast<size_t>(nv) + 1, 0);
  a.vertex_face.resize(static_cast<size_t>(3) * nf);
  for (const auto& t : tri)
    for (int v : t) ++a.vertex_begin[v + 1];
  for (int v = 0; v < nv; ++v) a.vertex_begin[v + 1] += a.vertex_begin[v];
  std::vector<int> fill(a.vertex_begin.begin(), a.vertex_begin.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int v : tri[f]) a.vertex_face[fill[v]++] = f;
  a.across.assign(static_cast<size_t>(3) * nf, -1);
  a.opposite.assign(static_cast<size_t>(3) * nf, -1);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = tri[f][k], v = tri[f][(k + 1) % 3];
      int other = -1, corner = -1, reverse = 0, same = 0;
      for (int i = a.vertex_begin[u]; i < a.vertex_begin[u + 1]; ++i) {
        const int h = a.vertex_face[i];
        const std::array<int, 3>& t = tri[h];
        for (int m = 0; m < 3; ++m) {
          const int p = t[m], q = t[(m + 1) % 3];
          if (p == v && q == u) other = h, corner = t[(m + 2) % 3], ++reverse;
          if (p == u && q == v && h != f) ++same;
        }
      }
      if (reverse == 1 && same == 0) a.across[3 * f + k] = other, a.opposite[3 * f + k] = corner;
    }
  }
  return a;
}

}  // namespace slim
