#include "core/support_model/overhang_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "core/domain/triangle_cells.h"
#include "core/geometry/convex_polygon.h"
#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"
#include "core/support_model/face_overhang.h"
#include "core/support_model/region_extent.h"

namespace slim {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// Pixels and object layers as the voxels of a grid: pixel (i, j) across, and along z the layer
// whose slice first meets a surface at that height, so the voxel (i, j, k) of a feature says "it
// shows in pixel (i, j) at layer k". Layer k >= 1 covers [slice_z(k - 1), slice_z(k)] with
// slice_z(k) = first + (k - 0.5) · height: grid z = (z - first) / height + 1.5 (the first layer's
// own thickness only shifts features below its slice, which get no support anyway).
struct LayerVoxels {
  VoxelGrid grid;
  double x0, y0, pixel;
  SlicePlanes planes;
  LayerVoxels(const PixelGrid& g, const OverhangRule& rule, double top)
      : x0(g.x0), y0(g.y0), pixel(g.pixel), planes{rule.first_layer_height, rule.layer_height} {
    grid.cells = Eigen::Vector3i(g.nx, g.ny, static_cast<int>(std::max(0.0, layer(top))) + 2);
  }
  double layer(double z) const { return (z - planes.first_height) / planes.height + 1.5; }
  // The slice heights around z: the top of the layer below z's layer and the top of z's layer.
  double slice_below(double z) const { return planes.slice_z(planes.layer_of(z) - 1); }
  double slice_above(double z) const { return planes.slice_z(planes.layer_of(z)); }
  Vec3 to_grid(const Vec3& p) const { return Vec3((p.x() - x0) / pixel, (p.y() - y0) / pixel, layer(p.z())); }
};

// Marks every pixel the feature (a triangle, or a segment a-b given as the triangle a, b, b)
// overlaps, with the layers it meets there: the voxel rasterizer of the domain, exact (closed
// cells, so a feature ending on a boundary touches both sides).
void mark_feature(const LayerVoxels& v, const Vec3& a, const Vec3& b, const Vec3& c, bool dense, std::vector<PixelOverhang>& out) {
  const int nx = v.grid.cells(0);
  int last = -1;
  cells_overlapping_triangle(v.grid, v.to_grid(a), v.to_grid(b), v.to_grid(c), 0.0, [&](int i, int j, int k) {
    const int pixel = i + nx * j;
    if (pixel == last && out.back().layer_high + 1 >= k) {  // k innermost: extend the run
      out.back().layer_high = std::max(out.back().layer_high, k);
      return;
    }
    out.push_back({pixel, k, k, dense});
    last = pixel;
  });
}

// Whether face vertex c lies above the line through a and b (at c's horizontal position), so the
// face rises away from the edge a-b. False for an edge seen end on.
bool rises_from(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec2 e = (b - a).head<2>();
  const double len2 = e.squaredNorm();
  if (!(len2 > 0)) return false;
  const double t = e.dot((c - a).head<2>()) / len2;
  return c.z() > a.z() + t * (b.z() - a.z());
}

// How far the slicer sees a convex bottom crease a-b (between faces of outward normals n1, n2)
// reach beyond the layer below, per unit of layer height. Layer by layer the slice has a corner
// where the crease meets the layer: the wedge {x : (x - tip)·m_i <= 0}, m_i the faces' outward
// normals in the plane. One layer up the tip has moved uphill along the crease by
// layer / tan(crease slope). The slicer grows the layer below by its reach with square corners
// (Clipper's square joins: each side pushed out by the reach, the corner cut square at the reach
// along its bisector) and calls what sticks out an overhang: the new tip's largest offset along
// m_1, m_2 and the bisector. A level crease appears all at once: infinite. 0 when the tip stays
// inside the old slice.
double crease_reach(const Vec3& a, const Vec3& b, const Vec3& n1, const Vec3& n2) {
  const Vec2 m1 = n1.head<2>(), m2 = n2.head<2>();
  if (!(m1.norm() > 0) || !(m2.norm() > 0)) return 0.0;  // a level face: its own rule covers it
  const Vec3 e = b.z() >= a.z() ? Vec3(b - a) : Vec3(a - b);
  if (!(e.z() > 0)) return INFINITY;
  const Vec2 tip = e.head<2>() / e.z();  // one unit of height up the crease
  const Vec2 w1 = m1.normalized(), w2 = m2.normalized(), mid = w1 + w2;
  double reach = std::max(tip.dot(w1), tip.dot(w2));
  if (mid.norm() > 1e-9) reach = std::max(reach, tip.dot(mid.normalized()));
  else reach = std::max(reach, tip.norm());  // a fold flat on itself: no corner to cut
  return std::max(0.0, reach);
}

// Triangle a, b, c clipped to the half-spaces n·p <= d (convex_polygon.h): at most 6 corners,
// fewer than 3 when nothing is left.
using Clipped = ConvexPolygon<6>;
Clipped clip_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const std::array<std::pair<Vec3, double>, 3>& planes) {
  Clipped poly, next;
  poly.p[0] = a, poly.p[1] = b, poly.p[2] = c, poly.n = 3;
  for (const auto& [n, d] : planes) {
    double dist[6];
    bool inside[6];
    for (int i = 0; i < poly.n; ++i) {
      dist[i] = n.dot(poly.p[static_cast<size_t>(i)]) - d;
      inside[i] = dist[i] <= 0;
    }
    clip_convex_polygon(poly, dist, inside, next);
    poly = next;
    if (poly.n < 3) break;
  }
  return poly;
}

// A clipped convex polygon marked as the fan of triangles from its first corner (nothing when fewer
// than 3 corners are left).
void mark_polygon(const LayerVoxels& voxels, const Clipped& part, bool dense, std::vector<PixelOverhang>& out) {
  for (int i = 1; i + 1 < part.n; ++i)
    mark_feature(voxels, part.p[0], part.p[static_cast<size_t>(i)], part.p[static_cast<size_t>(i + 1)], dense, out);
}

// The triangle a, b, c (or the segment a-b as a, b, b) marked between the heights shown.
void mark_feature_between(const LayerVoxels& voxels, const Vec3& a, const Vec3& b, const Vec3& c, const ShownHeights& shown,
                          bool dense, std::vector<PixelOverhang>& out) {
  if (std::min({a.z(), b.z(), c.z()}) >= shown.low && std::max({a.z(), b.z(), c.z()}) <= shown.high)
    return mark_feature(voxels, a, b, c, dense, out);
  const std::pair<Vec3, double> below{Vec3(0, 0, 1), shown.high}, above{Vec3(0, 0, -1), -shown.low};
  const Clipped part = clip_triangle(a, b, c, {below, above, above});
  mark_polygon(voxels, part, dense, out);
  if (part.n == 2) mark_feature(voxels, part.p[0], part.p[1], part.p[1], dense, out);
}

// Whether a face around vertex v reaches below it: the surface goes on down from v (a wall under it).
bool surface_goes_below(const Surface& s, const FaceAdjacency& adj, int v) {
  for (const int* f = adj.faces_begin(v); f != adj.faces_end(v); ++f)
    for (int q : adj.face(*f))
      if (s.V(q, 2) < s.V(v, 2)) return true;
  return false;
}
// The part, its faces' overhang and their regions' extents, the rule and the layer voxels: what
// every kind of feature is marked from. Each mark_* call takes a range of faces (vertices, for the
// tips) and appends its features to `out`, so the ranges can run on the threads.
class FeatureMarker {
 public:
  FeatureMarker(const Surface& s, const FaceAdjacency& adj, const PixelGrid& g, const OverhangRule& rule)
      : s_(s), adj_(adj), rule_(rule), voxels_(g, rule, s.V.col(2).maxCoeff()), faces_(face_overhangs(s, adj, rule)),
        extents_(region_extents(s, adj, region_mask(faces_))), margin_(slicer_margin(rule)) {}
  void mark_overhangs(Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) const;
  void mark_creases(Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) const;
  void mark_tips(Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) const;

 private:
  // An overhanging face as its strips across its edges need it: its run per height, the heights
  // it shows between, and whether it wants a dense interface.
  struct MarkedFace {
    double run;
    ShownHeights shown;
    bool dense;
  };
  void mark_strip_across(int g, const Vec3& a, const Vec3& b, const MarkedFace& face, std::vector<PixelOverhang>& out) const;
  static std::vector<char> region_mask(const std::vector<FaceOverhang>& faces) {
    std::vector<char> in(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) in[f] = faces[f].overhangs();
    return in;
  }
  Vec3 vertex(int v) const { return s_.V.row(v).transpose(); }

  const Surface& s_;
  const FaceAdjacency& adj_;
  const OverhangRule& rule_;
  const LayerVoxels voxels_;
  const std::vector<FaceOverhang> faces_;
  const std::vector<RegionExtent> extents_;
  const double margin_;  // how far a slice must reach past the slice below (slicer_margin)
};

// Bottom creases and lowest vertices: the first slice of a keel or a tip is an island with nothing
// below it, which slicers support whatever the slope of the faces around it. The faces around each
// vertex (counting sort, no hashing) give every edge's other face. Faces [first, end) for the
// creases; vertices [first, end) for the tips. A crease between two overhanging faces is their
// region's own: it is marked only where it bottoms out with nothing below it, where the faces'
// trimming in their lowest layer (region_extent.h, which reckons with a wall there) would drop the
// island. Where the surface goes on down from its lower end the faces show it, and the crease's
// tip, measured along it, would overstate how far the slice passes the wall's.
void FeatureMarker::mark_creases(Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) const {
  const double cos_max_slope = std::cos(rule_.max_slope_deg * M_PI / 180.0);
  const double cos2_max_slope = cos_max_slope * cos_max_slope;
  const double reach_overhang = 1.0 / std::tan(rule_.max_slope_deg * M_PI / 180.0);
  const double reach_dense = 1.0 / std::tan(rule_.dense_slope_deg * M_PI / 180.0);
  // Each edge once, from its lower face index: asked first when the twins are a lookup (half the
  // edges then need no position at all), else after the cheaper tests.
  const bool twins_first = adj_.has_every_twin();
  for (int f = static_cast<int>(first); f < end; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (twins_first && adj_.across(f, k).face < f) continue;
      const int u = s_.F(f, k), v = s_.F(f, (k + 1) % 3), w = s_.F(f, (k + 2) % 3);
      const Vec3 a = vertex(u), b = vertex(v), c = vertex(w), e = b - a;
      // The edge less steep than the threshold (cos of its slope = |e.xy| / |e| > cos(max slope)),
      // and this face rising away from it. Squares first: most edges are far steeper, and the
      // square roots and the division below decide only the rest, as they always did.
      const double level2 = e.head<2>().squaredNorm();
      if (level2 < 0.98 * cos2_max_slope * e.squaredNorm()) continue;
      const double len = e.norm();
      if (!(len > 0) || !(e.head<2>().norm() / len > cos_max_slope) || !rises_from(a, b, c)) continue;
      // Once per edge, manifold, the other face rising too, and convex: the other face's third
      // vertex behind this face's plane.
      const FaceAdjacency::Twin twin = adj_.across(f, k);
      if (twin.face < f) continue;
      if (faces_[f].overhangs() && faces_[twin.face].overhangs() && surface_goes_below(s_, adj_, a.z() < b.z() ? u : v)) continue;
      const Vec3 d = vertex(twin.opposite), n1 = (b - a).cross(c - a), n2 = (a - b).cross(d - b);
      if (!rises_from(b, a, d) || !(n1.dot(d - a) < 0)) continue;
      const double reach = crease_reach(a, b, n1, n2);
      if (!(reach > reach_overhang)) continue;
      const ShownHeights shown = shown_heights(std::min(a.z(), b.z()), std::max(a.z(), b.z()), reach,
                                               feature_extent(extents_, std::array<int, 2>{u, v}), voxels_.planes, margin_);
      mark_feature_between(voxels_, a, b, b, shown, reach > reach_dense, out);
    }
  }
}

void FeatureMarker::mark_tips(Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) const {
  for (int v = static_cast<int>(first); v < end; ++v) {
    if (adj_.faces_end(v) - adj_.faces_begin(v) < 3) continue;
    // Below every neighbour; most vertices have one no higher among their first face's.
    const double z = s_.V(v, 2);
    bool lowest = true;
    for (const int* f = adj_.faces_begin(v); f != adj_.faces_end(v) && lowest; ++f)
      for (int u : adj_.face(*f))
        if (u != v && !(z < s_.V(u, 2))) lowest = false;
    if (!lowest) continue;
    const Vec3 p = vertex(v);
    mark_feature(voxels_, p, p, p, true, out);
  }
}

// Where an overhang region ends across edge a-b on a face g that looks down but is steeper (or a
// dropped lip), the slicer's overhang in the layers of that edge reaches onto g: it grows what
// passes its threshold back by one layer's reach, kept to the layer's own strip. Marks g's part
// between the slices around the edge and within the reach of it (beyond the edge, away from the
// overhanging face, whose run per height is face.run). Where g lies below the edge that is all of
// it. Where g lies above it (an underside curving up into a steeper side), the slice below lies on
// the overhanging face, and in layer k only the part of g farther than the reach from the slice at
// slice_z(k - 1) is contact (PrusaSlicer takes what lies within its margin of the slice below out
// of its contacts: the slices_margin of detect_overhangs): at a point of g that is
// (z_e - slice_z(k - 1)) run back to the edge at its height z_e, plus its own distance beyond it.
void FeatureMarker::mark_strip_across(int g, const Vec3& a, const Vec3& b, const MarkedFace& face,
                                      std::vector<PixelOverhang>& out) const {
  const Vec3 p = vertex(s_.F(g, 0)), q = vertex(s_.F(g, 1)), r = vertex(s_.F(g, 2)), centre = (p + q + r) / 3.0;
  const Vec2 e = (b - a).head<2>();
  if (!((q - p).cross(r - p).z() < 0) || !(e.norm() > 0)) return;  // g looks up or sideways; an edge end on
  Vec2 away = Vec2(e.y(), -e.x()).normalized();
  if (away.dot((centre - a).head<2>()) < 0) away = -away;  // towards g
  // Inside the slices by a hair: the voxel cells are closed, and a strip ending on a slice would
  // touch the layer beyond it too.
  const double z_low = std::max(face.shown.low, voxels_.slice_below(std::min(a.z(), b.z())) + 1e-6);
  const double z_high = std::min(face.shown.high, voxels_.slice_above(std::max(a.z(), b.z())) - 1e-6);
  const Clipped strip = clip_triangle(p, q, r, {{{Vec3(0, 0, -1), -z_low}, {Vec3(0, 0, 1), z_high},
                                                  {Vec3(away.x(), away.y(), 0), away.dot(a.head<2>()) + margin_}}});
  const Vec2 along = e / e.norm();
  const double edge_rise = (b.z() - a.z()) / e.norm();  // the edge's height per mm along it
  const bool above = centre.z() > a.z() + edge_rise * along.dot((centre - a).head<2>());
  if (!above || !std::isfinite(face.run)) return mark_polygon(voxels_, strip, face.dense, out);
  // Layer by layer: the part of the strip in layer k where (z_e - slice_z(k - 1)) run + the
  // distance beyond the edge passes the reach, a half-plane w.xy <= d since z_e is linear along it.
  const SlicePlanes& planes = voxels_.planes;
  const Vec2 w = -face.run * edge_rise * along - away;
  for (double k = planes.layer_of(z_low); planes.slice_z(k - 1) < z_high; k += 1) {
    const double below = planes.slice_z(k - 1), d = w.dot(a.head<2>()) + face.run * (a.z() - below) - margin_;
    for (int i = 1; i + 1 < strip.n; ++i)
      mark_polygon(voxels_,
                   clip_triangle(strip.p[0], strip.p[static_cast<size_t>(i)], strip.p[static_cast<size_t>(i + 1)],
                                 {{{Vec3(0, 0, -1), -(below + 1e-6)}, {Vec3(0, 0, 1), planes.slice_z(k) - 1e-6}, {Vec3(w.x(), w.y(), 0), d}}}),
                   face.dense, out);
  }
}

// The overhanging faces [first, end) (face_overhang.h) marked, and those on a region's edge grown
// across their edges onto the steeper faces beside them (mark_strip_across). Not along the
// outline: the slicer grows each overhang back by the margin, but then takes what lies within the
// margin of the slice below out of its contacts (slices_margin in its detect_overhangs). Read so, a
// strip onto a steeper face below the edge would go too; it stays because PrusaSlicer does support
// the row of cells only that strip reaches under a bore's ceiling
// (Corpus.TheSupportModelPredictsPrusaSlicersChangeOnTheHinge). A strip onto a face above the edge
// is held to that margin.
void FeatureMarker::mark_overhangs(Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) const {
  for (int f = static_cast<int>(first); f < end; ++f) {
    const FaceOverhang& overhang = faces_[f];
    if (!overhang.overhangs()) continue;
    const Vec3 a = vertex(s_.F(f, 0)), b = vertex(s_.F(f, 1)), c = vertex(s_.F(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    const double run = n.head<2>().norm() > 0 ? -n.z() / n.head<2>().norm() : INFINITY;  // per height
    const ShownHeights shown = shown_heights(std::min({a.z(), b.z(), c.z()}), std::max({a.z(), b.z(), c.z()}), run,
                                             feature_extent(extents_, s_.F.row(f)), voxels_.planes, margin_);
    mark_feature_between(voxels_, a, b, c, shown, overhang.dense(), out);
    if (!overhang.region_edge || !(n.head<2>().norm() > 0)) continue;
    const MarkedFace face{run, shown, overhang.dense()};
    for (int k = 0; k < 3; ++k) {
      const int g = adj_.across(f, k).face;
      if (g >= 0 && !faces_[g].overhangs()) mark_strip_across(g, vertex(s_.F(f, k)), vertex(s_.F(f, (k + 1) % 3)), face, out);
    }
  }
}

}  // namespace

std::vector<PixelOverhang> overhang_features(const Surface& s, const FaceAdjacency& adj, const PixelGrid& g, const OverhangRule& rule) {
  const FeatureMarker marker(s, adj, g, rule);
  using Part = std::vector<PixelOverhang>;
  Part out = gather_in_ranges<PixelOverhang>(s.F.rows(), [&](Eigen::Index a, Eigen::Index b, Part& part) { marker.mark_overhangs(a, b, part); });
  for (const Part& more :
       {rule.creases ? gather_in_ranges<PixelOverhang>(
                           s.F.rows(), [&](Eigen::Index a, Eigen::Index b, Part& part) { marker.mark_creases(a, b, part); })
                     : Part{},
        rule.tips ? gather_in_ranges<PixelOverhang>(
                        s.V.rows(), [&](Eigen::Index a, Eigen::Index b, Part& part) { marker.mark_tips(a, b, part); })
                  : Part{}})
    out.insert(out.end(), more.begin(), more.end());
  return out;
}

}  // namespace slim
