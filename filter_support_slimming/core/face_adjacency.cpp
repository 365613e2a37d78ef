#include "core/face_adjacency.h"

namespace slim {

FaceAdjacency face_adjacency(const Surface& s) {
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  FaceAdjacency a;
  a.vertex_begin.assign(static_cast<size_t>(nv) + 1, 0);
  a.vertex_face.resize(static_cast<size_t>(3) * nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) ++a.vertex_begin[s.F(f, k) + 1];
  for (int v = 0; v < nv; ++v) a.vertex_begin[v + 1] += a.vertex_begin[v];
  std::vector<int> fill(a.vertex_begin.begin(), a.vertex_begin.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) a.vertex_face[fill[s.F(f, k)]++] = f;
  a.across.assign(static_cast<size_t>(3) * nf, -1);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
      int other = -1, reverse = 0, same = 0;
      for (int i = a.vertex_begin[u]; i < a.vertex_begin[u + 1]; ++i) {
        const int h = a.vertex_face[i];
        for (int m = 0; m < 3; ++m) {
          const int p = s.F(h, m), q = s.F(h, (m + 1) % 3);
          if (p == v && q == u) other = h, ++reverse;
          if (p == u && q == v && h != f) ++same;
        }
      }
      if (reverse == 1 && same == 0) a.across[3 * f + k] = other;
    }
  }
  return a;
}

}  // namespace slim
