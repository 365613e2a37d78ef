#include "core/geometry/surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace slim {

Points face_normals(const Surface& s) { return face_normals(s.V, s.F); }

Points face_normals(const Points& V, const Triangles& F) {
  Points n(F.rows(), 3);
#pragma omp parallel for schedule(static) if (F.rows() > 65536)
  for (Eigen::Index f = 0; f < F.rows(); ++f) n.row(f) = unit_normal(face_cross(V, F, f)).transpose();  // zero: in no constraint
  return n;
}

Eigen::VectorXd face_areas(const Surface& s) {
  Eigen::VectorXd a(s.F.rows());
#pragma omp parallel for schedule(static) if (s.F.rows() > 65536)
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) a(f) = 0.5 * face_cross(s.V, s.F, f).norm();
  return a;
}

double bbox_diagonal(const Points& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

void check_surface(const Surface& s) {
  if (!s.V.allFinite())
    for (Eigen::Index v = 0; v < s.V.rows(); ++v)
      if (!s.V.row(v).allFinite())
        throw std::invalid_argument("vertex " + std::to_string(v) +
                                    " has a NaN or infinite coordinate; repair or remove it (if no face uses it, "
                                    "removing the unreferenced vertices does it)");
  const Eigen::Index nv = s.V.rows();
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (s.F(f, k) < 0 || s.F(f, k) >= nv)
        throw std::invalid_argument("face " + std::to_string(f) + " refers to vertex " + std::to_string(s.F(f, k)) +
                                    ", but the mesh has " + std::to_string(nv) + " vertices");
}

std::vector<Eigen::Index> face_vertices(const Surface& s) {
  std::vector<bool> used(static_cast<size_t>(s.V.rows()), false);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[static_cast<size_t>(s.F(f, k))] = true;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index v = 0; v < s.V.rows(); ++v)
    if (used[static_cast<size_t>(v)]) kept.push_back(v);
  return kept;
}

double signed_volume(const Surface& s) {
  if (s.V.rows() == 0) return 0.0;
  // Far from the origin the terms a·(b×c) dwarf their sum; about the centroid they do not.
  const Eigen::RowVector3d centre = s.V.colwise().mean();
  double vol = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = (s.V.row(s.F(f, 0)) - centre).transpose();
    const Eigen::Vector3d b = (s.V.row(s.F(f, 1)) - centre).transpose();
    const Eigen::Vector3d c = (s.V.row(s.F(f, 2)) - centre).transpose();
    vol += a.dot(b.cross(c));
  }
  return vol / 6.0;
}

EdgeTopology edge_topology(const Surface& s) {
  struct HalfEdge {
    int hi;
    bool forward;
    int face;
  };
  // The half-edges of the faces with three vertices, bucketed by their lower vertex (a counting
  // sort), each bucket sorted by (higher vertex, face): the order of a sort by (lo, hi, face).
  const Eigen::Index nv = s.V.rows();
  auto proper = [&](Eigen::Index f) { return s.F(f, 0) != s.F(f, 1) && s.F(f, 1) != s.F(f, 2) && s.F(f, 2) != s.F(f, 0); };
  std::vector<int> begin(static_cast<size_t>(nv) + 1, 0);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (proper(f))
      for (int k = 0; k < 3; ++k) ++begin[static_cast<size_t>(std::min(s.F(f, k), s.F(f, (k + 1) % 3))) + 1];
  for (size_t v = 0; v < static_cast<size_t>(nv); ++v) begin[v + 1] += begin[v];
  std::vector<HalfEdge> edges(static_cast<size_t>(begin.back()));
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (proper(f))
      for (int k = 0; k < 3; ++k) {
        const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
        edges[static_cast<size_t>(fill[static_cast<size_t>(std::min(a, b))]++)] = {std::max(a, b), a < b, static_cast<int>(f)};
      }
  EdgeTopology t;
  for (Eigen::Index lo = 0; lo < nv; ++lo) {
    const auto first = edges.begin() + begin[static_cast<size_t>(lo)], last = edges.begin() + begin[static_cast<size_t>(lo) + 1];
    std::sort(first, last, [](const HalfEdge& x, const HalfEdge& y) { return std::tie(x.hi, x.face) < std::tie(y.hi, y.face); });
    for (auto i = first; i != last;) {
      auto j = i;
      while (j != last && j->hi == i->hi) ++j;
      auto name = [&] { return "(" + std::to_string(lo) + ", " + std::to_string(i->hi) + ")"; };
      if (j - i == 1) {
        if (t.open_edges++ == 0) t.first_open = name();
      } else if (j - i > 2) {
        if (t.nonmanifold_edges++ == 0) t.first_nonmanifold = name() + " is shared by " + std::to_string(j - i) + " faces";
      } else if (i->forward == (i + 1)->forward) {
        if (t.flipped_edges++ == 0)
          t.first_flipped = "faces " + std::to_string(i->face) + " and " + std::to_string((i + 1)->face) + " run along edge " +
                            name() + " in the same direction";
      }
      i = j;
    }
  }
  return t;
}

void require_consistent_orientation(const EdgeTopology& edges) {
  if (edges.flipped_edges > 0)
    throw std::invalid_argument("the faces are not consistently oriented (" + edges.first_flipped + "; " +
                                std::to_string(edges.flipped_edges) +
                                " such edge(s)), so their normals do not tell the outside of the part; re-orient "
                                "the faces coherently (MeshLab: Filters > Normals, Curvatures and Orientation > "
                                "Re-Orient all faces coherently)");
}

bool inside_out(const Surface& s, const EdgeTopology& edges) {
  return edges.open_edges == 0 && edges.flipped_edges == 0 && s.F.rows() > 0 && signed_volume(s) < 0.0;
}

Surface flipped(const Surface& s) {
  Surface out = s;
  out.F.col(1).swap(out.F.col(2));
  return out;
}

}  // namespace slim
