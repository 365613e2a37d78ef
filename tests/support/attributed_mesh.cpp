#include "support/attributed_mesh.h"

#include <cstdio>
#include <stdexcept>

#include "support/shapes.h"

namespace slim::test {
namespace {

int append_vertex(Surface& s, const Eigen::RowVector3d& p) {
  s.V.conservativeResize(s.V.rows() + 1, 3);
  s.V.row(s.V.rows() - 1) = p;
  return static_cast<int>(s.V.rows()) - 1;
}

int find_vertex(const Surface& s, const Eigen::RowVector3d& p) {
  for (Eigen::Index i = 0; i < s.V.rows(); ++i)
    if (s.V.row(i) == p) return static_cast<int>(i);
  throw std::logic_error("attributed_mesh: no vertex at the point");
}

}  // namespace

AttributedMesh attributed_mesh() {
  AttributedMesh m;
  // The lower box on the plate and the middle one on its corner (10, 10, 10), welded: one vertex.
  Surface s = weld(merge(box({0, 0, 0}, {10, 10, 10}), box({10, 10, 10}, {20, 20, 20})));
  m.shared_corner = find_vertex(s, {10, 10, 10});
  // The top box on the middle one's corner (20, 20, 20), with its own vertex there.
  s = merge(s, box({20, 20, 20}, {30, 30, 30}));
  m.coincident_corner = static_cast<int>(s.V.rows()) - 8 + find_vertex(box({20, 20, 20}, {30, 30, 30}), {20, 20, 20});
  // A seam: the first face that uses the lower box's corner (0, 0, 0) uses a copy of it instead.
  m.seam_original = find_vertex(s, {0, 0, 0});
  m.seam_copy = append_vertex(s, s.V.row(m.seam_original));
  for (Eigen::Index f = 0; f < s.F.rows() && m.seam_copy >= 0; ++f) {
    bool done = false;
    for (int k = 0; k < 3 && !done; ++k)
      if (s.F(f, k) == m.seam_original) s.F(f, k) = m.seam_copy, done = true;
    if (done) break;
  }
  m.unreferenced_copy = append_vertex(s, s.V.row(m.seam_original));
  m.unreferenced_apart = append_vertex(s, {40, 0, 5});
  m.surface = s;

  const Eigen::Index n = s.V.rows();
  m.colour.resize(n, 4);
  m.texcoord.resize(n, 2);
  m.normal.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    m.colour.row(i) << static_cast<unsigned char>(7 * i % 256), static_cast<unsigned char>(255 - 5 * i % 256),
        static_cast<unsigned char>(11 * i % 256), static_cast<unsigned char>(200 + i % 50);
    m.texcoord.row(i) << static_cast<double>(i) / 64.0, 1.0 - static_cast<double>(i % 64) / 64.0;
    m.normal.row(i) = Eigen::RowVector3d(1.0 + static_cast<double>(i), 2.0, -3.0).normalized();
  }
  return m;
}

void write_attributed_ply(const std::string& path, const AttributedMesh& m) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  const Surface& s = m.surface;
  std::fprintf(f,
               "ply\nformat ascii 1.0\nelement vertex %ld\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\n"
               "property uchar blue\nproperty uchar alpha\nproperty float texture_u\nproperty float texture_v\n"
               "element face %ld\nproperty list uchar int vertex_indices\nend_header\n",
               static_cast<long>(s.V.rows()), static_cast<long>(s.F.rows()));
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    std::fprintf(f, "%.9g %.9g %.9g %.9g %.9g %.9g %d %d %d %d %.9g %.9g\n", s.V(v, 0), s.V(v, 1), s.V(v, 2),
                 static_cast<double>(static_cast<float>(m.normal(v, 0))), static_cast<double>(static_cast<float>(m.normal(v, 1))),
                 static_cast<double>(static_cast<float>(m.normal(v, 2))), m.colour(v, 0), m.colour(v, 1), m.colour(v, 2),
                 m.colour(v, 3), m.texcoord(v, 0), m.texcoord(v, 1));
  for (Eigen::Index t = 0; t < s.F.rows(); ++t) std::fprintf(f, "3 %d %d %d\n", s.F(t, 0), s.F(t, 1), s.F(t, 2));
  std::fclose(f);
}

}  // namespace slim::test
