#include "orient_faces.h"

#include <algorithm>
#include <vector>

#include <Eigen/Geometry>

#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/clean.h>
#include <vcg/complex/algorithms/update/topology.h>

namespace slim::eval {
namespace {

class OVertex;
class OFace;
struct OTypes : vcg::UsedTypes<vcg::Use<OVertex>::AsVertexType, vcg::Use<OFace>::AsFaceType> {};
class OVertex : public vcg::Vertex<OTypes, vcg::vertex::Coord3d, vcg::vertex::BitFlags> {};
class OFace : public vcg::Face<OTypes, vcg::face::VertexRef, vcg::face::FFAdj, vcg::face::Mark, vcg::face::BitFlags> {};
class OMesh : public vcg::tri::TriMesh<std::vector<OVertex>, std::vector<OFace>> {};

// Connected pieces over shared edges (FF adjacency), one label per face.
std::vector<int> pieces(OMesh& m) {
  std::vector<int> label(m.face.size(), -1);
  int next = 0;
  for (size_t seed = 0; seed < m.face.size(); ++seed) {
    if (label[seed] >= 0) continue;
    std::vector<OFace*> stack = {&m.face[seed]};
    label[seed] = next;
    while (!stack.empty()) {
      OFace* f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        OFace* g = f->FFp(k);
        const size_t gi = static_cast<size_t>(vcg::tri::Index(m, g));
        if (label[gi] < 0) label[gi] = next, stack.push_back(g);
      }
    }
    ++next;
  }
  return label;
}

// The faces that name three different vertices, in order.
Surface without_repeated_vertices(const Surface& s) {
  Surface out{s.V, Triangles(s.F.rows(), 3)};
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (s.F(f, 0) != s.F(f, 1) && s.F(f, 1) != s.F(f, 2) && s.F(f, 2) != s.F(f, 0)) out.F.row(kept++) = s.F.row(f);
  out.F.conservativeResize(kept, 3);
  return out;
}

}  // namespace

OrientedFaces orient_faces(const Surface& input) {
  check_surface(input);
  const Surface s = without_repeated_vertices(input);
  OMesh m;
  vcg::tri::Allocator<OMesh>::AddVertices(m, static_cast<size_t>(s.V.rows()));
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) m.vert[v].P() = vcg::Point3d(s.V(v, 0), s.V(v, 1), s.V(v, 2));
  vcg::tri::Allocator<OMesh>::AddFaces(m, static_cast<size_t>(s.F.rows()));
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) m.face[f].V(k) = &m.vert[s.F(f, k)];
  vcg::tri::UpdateTopology<OMesh>::FaceFace(m);
  bool oriented = false, orientable = true;
  vcg::tri::Clean<OMesh>::OrientCoherentlyMesh(m, oriented, orientable);

  OrientedFaces out;
  out.dropped = input.F.rows() - s.F.rows();
  out.orientable = orientable;
  out.surface = s;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.surface.F(f, k) = static_cast<int>(vcg::tri::Index(m, m.face[f].V(k)));
  // Each piece outward: the volume it encloses (about the mesh's centroid) must be positive.
  const std::vector<int> label = pieces(m);
  const int n = label.empty() ? 0 : *std::max_element(label.begin(), label.end()) + 1;
  const Eigen::RowVector3d c = s.V.colwise().mean();
  std::vector<double> volume(static_cast<size_t>(n), 0.0);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::RowVector3d a = s.V.row(out.surface.F(f, 0)) - c, b = s.V.row(out.surface.F(f, 1)) - c,
                             d = s.V.row(out.surface.F(f, 2)) - c;
    volume[static_cast<size_t>(label[f])] += a.dot(b.cross(d)) / 6.0;
  }
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (volume[static_cast<size_t>(label[f])] < 0) std::swap(out.surface.F(f, 1), out.surface.F(f, 2));
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    // Turned over: the same cycle of vertices in the other direction.
    const Eigen::RowVector3i a = s.F.row(f), b = out.surface.F.row(f);
    const bool same = (a == b) || (a == Eigen::RowVector3i(b(1), b(2), b(0))) || (a == Eigen::RowVector3i(b(2), b(0), b(1)));
    if (!same) ++out.flipped;
  }
  return out;
}

}  // namespace slim::eval
