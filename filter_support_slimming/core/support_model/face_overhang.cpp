#include "core/support_model/face_overhang.h"

#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"
#include "core/utilities/union_find.h"

namespace slim {
namespace {

using Vec3 = Eigen::Vector3d;
using Kind = FaceOverhang::Kind;

// The faces less steep than the threshold, by their slope alone.
std::vector<FaceOverhang> by_slope(const Surface& s, const OverhangRule& rule) {
  const int nf = static_cast<int>(s.F.rows());
  const double cos_max = std::cos(rule.max_slope_deg * M_PI / 180.0), cos_dense = std::cos(rule.dense_slope_deg * M_PI / 180.0);
  std::vector<FaceOverhang> faces(static_cast<size_t>(nf));
  parallel_for(nf, [&](int f) {
    const Vec3 n = face_cross(s.V, s.F, f);
    const double len = n.norm();
    const double down = len > 0 ? -n.z() / len : 0.0;  // cos of the slope, for a face looking down
    faces[f].kind = down > cos_max ? (down > cos_dense ? Kind::Dense : Kind::Overhang) : Kind::None;
  });
  return faces;
}

// Per region (at its root): projected area, outline, sum of area × tan(slope), and along the
// outline the length next to faces that look down or sideways, and that length × their cot.
struct Region {
  double area = 0.0, outline = 0.0, area_tan = 0.0, side = 0.0, side_cot = 0.0;
  // How far the region reaches beyond the layer below (mm; face_overhang.h).
  double reach(double layer_height) const {
    if (!(outline > 0 && area > 0)) return INFINITY;
    const double width = 2.0 * area / outline, tan_slope = area_tan / area;
    const double cot_around = side > 0 ? side_cot / side : 0.0;
    return width + std::max(0.0, layer_height - width * tan_slope) * cot_around;
  }
};

// The overhanging faces in increasing order, with their normals, neighbours and regions (a few of
// the faces; the rest need none of it).
struct Overhanging {
  std::vector<int> face;
  std::vector<Vec3> normal;
  std::vector<std::array<int, 3>> across;
  Overhanging(const Surface& s, const FaceAdjacency& adj, const std::vector<FaceOverhang>& faces) {
    for (int f = 0; f < static_cast<int>(faces.size()); ++f)
      if (faces[f].overhangs()) face.push_back(f);
    const int no = static_cast<int>(face.size());
    normal.resize(static_cast<size_t>(no));
    across.resize(static_cast<size_t>(no));
    parallel_for(no, [&](int i) {
      normal[i] = face_cross(s.V, s.F, face[i]);
      for (int k = 0; k < 3; ++k) across[i][k] = adj.across(face[i], k).face;
    });
  }
};

std::vector<Region> regions_of(const Surface& s, const std::vector<FaceOverhang>& faces, const Overhanging& over,
                               UnionFind& regions) {
  const int no = static_cast<int>(over.face.size());
  std::vector<int> slot(faces.size(), -1);
  for (int i = 0; i < no; ++i) slot[over.face[i]] = i;
  for (int i = 0; i < no; ++i)
    for (int k = 0; k < 3; ++k) {
      const int g = over.across[i][k];
      if (g >= 0 && faces[g].overhangs()) regions.join(i, slot[g]);
    }
  std::vector<Region> region(static_cast<size_t>(no));
  for (int i = 0; i < no; ++i) {
    const int f = over.face[i];
    Region& r = region[regions.find(i)];
    const Vec3& n = over.normal[i];
    r.area += 0.5 * std::abs(n.z());
    r.area_tan += 0.5 * n.head<2>().norm();  // projected area × tan(slope) = half the normal's horizontal part
    for (int k = 0; k < 3; ++k) {
      const int g = over.across[i][k];
      if (g >= 0 && faces[g].overhangs()) continue;
      const double length = (s.V.row(s.F(f, (k + 1) % 3)) - s.V.row(s.F(f, k))).head<2>().norm();
      r.outline += length;
      if (g < 0) continue;
      const Vec3 ng = face_cross(s.V, s.F, g);
      if (ng.z() > 0 || !(ng.head<2>().norm() > 0)) continue;
      r.side += length;
      r.side_cot += length * -ng.z() / ng.head<2>().norm();
    }
  }
  return region;
}

}  // namespace

double slicer_margin(const OverhangRule& rule) { return rule.layer_height / std::tan(rule.max_slope_deg * M_PI / 180.0); }

std::vector<FaceOverhang> face_overhangs(const Surface& s, const FaceAdjacency& adj, const OverhangRule& rule) {
  std::vector<FaceOverhang> faces = by_slope(s, rule);
  const Overhanging over(s, adj, faces);
  const int no = static_cast<int>(over.face.size());
  UnionFind regions(no);
  const std::vector<Region> region = regions_of(s, faces, over, regions);
  const double reach = slicer_margin(rule);
  const double reach_dense = rule.layer_height / std::tan(rule.dense_slope_deg * M_PI / 180.0);
  for (int i = 0; i < no; ++i) {
    FaceOverhang& face = faces[over.face[i]];
    const double seen = region[regions.find(i)].reach(rule.layer_height);
    face.kind = seen > 0.5 * reach ? (face.dense() && seen > reach_dense ? Kind::Dense : Kind::Overhang) : Kind::None;
  }
  for (int i = 0; i < no; ++i) {  // on the edge of its region: a side with no overhanging face
    FaceOverhang& face = faces[over.face[i]];
    for (int k = 0; k < 3 && face.overhangs() && !face.region_edge; ++k) {
      const int g = over.across[i][k];
      if (g < 0 || !faces[g].overhangs()) face.region_edge = true;
    }
  }
  return faces;
}

}  // namespace slim
