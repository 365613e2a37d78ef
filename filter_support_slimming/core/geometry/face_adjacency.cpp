#include "core/geometry/face_adjacency.h"

#include "core/platform/parallel_for.h"

namespace slim {

FaceAdjacency::FaceAdjacency(const Surface& s) : FaceAdjacency(s.F, s.V.rows(), false) {}

FaceAdjacency::FaceAdjacency(const Triangles& F, Eigen::Index vertices, bool every_twin) {
  const int nv = static_cast<int>(vertices), nf = static_cast<int>(F.rows());
  tri_.resize(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) tri_[f] = {F(f, 0), F(f, 1), F(f, 2)};
  vertex_begin_.assign(static_cast<size_t>(nv) + 1, 0);
  vertex_face_.resize(static_cast<size_t>(3) * nf);
  for (const auto& t : tri_)
    for (int v : t) ++vertex_begin_[v + 1];
  for (int v = 0; v < nv; ++v) vertex_begin_[v + 1] += vertex_begin_[v];
  std::vector<int> fill(vertex_begin_.begin(), vertex_begin_.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int v : tri_[f]) vertex_face_[fill[v]++] = f;
  if (!every_twin) return;
  std::vector<Twin> twins(static_cast<size_t>(3) * nf);
  parallel_for(nf, [&](int f) {
    for (int k = 0; k < 3; ++k) twins[3 * static_cast<size_t>(f) + k] = find_twin(f, k);
  });
  twins_ = std::move(twins);
}

FaceAdjacency::Twin FaceAdjacency::across(int f, int k) const {
  return twins_.empty() ? find_twin(f, k) : twins_[3 * static_cast<size_t>(f) + k];
}

FaceAdjacency::Twin FaceAdjacency::find_twin(int f, int k) const {
  const int u = tri_[f][k], v = tri_[f][(k + 1) % 3];
  Twin twin;
  int reverse = 0, same = 0;
  for (const int* h = faces_begin(u); h != faces_end(u); ++h) {
    const std::array<int, 3>& t = tri_[*h];
    for (int m = 0; m < 3; ++m) {
      const int p = t[m], q = t[(m + 1) % 3];
      if (p == v && q == u) twin = {*h, t[(m + 2) % 3]}, ++reverse;
      if (p == u && q == v && *h != f) ++same;
    }
  }
  return reverse == 1 && same == 0 ? twin : Twin{};
}

}  // namespace slim
