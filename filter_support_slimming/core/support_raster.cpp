#include "core/support_raster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <Eigen/Geometry>

#include "core/face_adjacency.h"
#include "core/parallel_for.h"
#include "core/slice_raster.h"
#include "core/triangle_cells.h"
#include "core/union_find.h"

namespace slim {
namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Which side of the directed edge p -> q the point s lies on, never 0: the edge function
// cross(q - p, s - p), and for a point exactly on the edge the sign it has at s + (eps, eps²) for an
// infinitesimal eps (simulation of simplicity). Evaluated from the edge's lower vertex index, so the
// two faces of an edge see exactly opposite signs: every ray crosses a closed surface an even
// number of times, also through shared edges and vertices.
int edge_side(const Vec2& p, int ip, const Vec2& q, int iq, const Vec2& s) {
  const bool swap = iq < ip;
  const Vec2& a = swap ? q : p;
  const Vec2& b = swap ? p : q;
  const Vec2 e = b - a;
  const double f = cross2(e, s - a);
  int side = f > 0 ? 1 : (f < 0 ? -1 : 0);
  if (side == 0) side = e.y() != 0 ? (e.y() < 0 ? 1 : -1) : (e.x() > 0 ? 1 : -1);
  return swap ? -side : side;
}

struct Crossing {
  int pixel;
  double z;
  int winding;  // +1 entering the solid going up (a face looking down), -1 leaving it
  bool operator<(const Crossing& o) const {
    if (pixel != o.pixel) return pixel < o.pixel;
    if (z != o.z) return z < o.z;
    return winding < o.winding;
  }
};

// Pixel index range [lo, hi] of the pixel centres that a 1D extent [a, b] reaches, clamped to
// [0, n - 1]; lo > hi when none.
void pixel_range(double a, double b, double origin, double pixel, int n, int& lo, int& hi) {
  const double u = (a - origin) / pixel, v = (b - origin) / pixel;
  const double l = std::ceil(u - 0.5), h = std::floor(v - 0.5);
  lo = static_cast<int>(std::max(0.0, std::min(l, static_cast<double>(n))));
  hi = static_cast<int>(std::max(-1.0, std::min(h, static_cast<double>(n - 1))));
}

// Stable counting sort of items by their pixel, then each pixel's items by `less`.
template <class T, class Less>
void sort_by_pixel(std::vector<T>& items, int pixels, Less less) {
  std::vector<int> begin(static_cast<size_t>(pixels) + 1, 0);
  for (const T& t : items) ++begin[t.pixel + 1];
  for (int p = 0; p < pixels; ++p) begin[p + 1] += begin[p];
  std::vector<T> sorted(items.size());
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (const T& t : items) sorted[fill[t.pixel]++] = t;
  // Pixels apart on the threads, in 64 ranges (a pixel's items end the same on any thread count).
  const int ranges = items.size() >= 65536 ? 64 : 1;
  parallel_for(ranges, [&](int r) {
    for (int p = static_cast<int>(static_cast<long>(pixels) * r / ranges); p < static_cast<long>(pixels) * (r + 1) / ranges; ++p)
      if (begin[p + 1] - begin[p] > 1) std::sort(sorted.begin() + begin[p], sorted.begin() + begin[p + 1], less);
  });
  items.swap(sorted);
}

// The rays through the pixel centres that face f crosses, appended to `out`.
void cross_rays(const Surface& s, const PixelGrid& g, Eigen::Index f, std::vector<Crossing>& out) {
  const int id[3] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
  const Vec3 p[3] = {s.V.row(id[0]).transpose(), s.V.row(id[1]).transpose(), s.V.row(id[2]).transpose()};
  const Vec2 q[3] = {p[0].head<2>(), p[1].head<2>(), p[2].head<2>()};
  const double area2 = cross2(q[1] - q[0], q[2] - q[0]);
  if (!(std::abs(area2) > 0)) return;  // seen edge on: no ray crosses it
  const int orient = area2 > 0 ? 1 : -1;  // +1: counter-clockwise from above, looking up
  int i0, i1, j0, j1;
  pixel_range(std::min({q[0].x(), q[1].x(), q[2].x()}), std::max({q[0].x(), q[1].x(), q[2].x()}), g.x0, g.pixel, g.nx, i0, i1);
  pixel_range(std::min({q[0].y(), q[1].y(), q[2].y()}), std::max({q[0].y(), q[1].y(), q[2].y()}), g.y0, g.pixel, g.ny, j0, j1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const Vec2 c(g.x0 + (i + 0.5) * g.pixel, g.y0 + (j + 0.5) * g.pixel);
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k)
        inside = edge_side(q[k], id[k], q[(k + 1) % 3], id[(k + 1) % 3], c) == orient;
      if (!inside) continue;
      const double w0 = cross2(q[1] - c, q[2] - c), w1 = cross2(q[2] - c, q[0] - c);
      const double z = (w0 * p[0].z() + w1 * p[1].z() + (area2 - w0 - w1) * p[2].z()) / area2;
      out.push_back({i + g.nx * j, z, -orient});
    }
  }
}

// The solid spans: every face crossed by the rays through the pixel centres, then nonzero winding
// along each ray.
void rasterize_solid(const Surface& s, const PixelGrid& g, SupportRaster& out) {
  std::vector<Crossing> crossings =
      gather_in_ranges<Crossing>(s.F.rows(), [&](Eigen::Index first, Eigen::Index end, std::vector<Crossing>& part) {
        for (Eigen::Index f = first; f < end; ++f) cross_rays(s, g, f, part);
      });
  sort_by_pixel(crossings, g.count(), [](const Crossing& x, const Crossing& y) { return x < y; });
  out.span_begin.assign(static_cast<size_t>(g.count()) + 1, 0);
  out.spans.clear();
  size_t c = 0;
  for (int pixel = 0; pixel < g.count(); ++pixel) {
    out.span_begin[pixel] = static_cast<int>(out.spans.size());
    int winding = 0;
    double start = 0.0, last = 0.0;
    for (; c < crossings.size() && crossings[c].pixel == pixel; ++c) {
      const int before = winding;
      winding += crossings[c].winding;
      last = crossings[c].z;
      if (before == 0 && winding != 0) start = last;
      if (before != 0 && winding == 0) out.spans.push_back({start, last});
    }
    if (winding != 0) out.spans.push_back({start, last});  // an open surface: close the ray
  }
  out.span_begin[g.count()] = static_cast<int>(out.spans.size());
}

// Pixels and object layers as the voxels of a grid: pixel (i, j) across, and along z the layer
// whose slice first meets a surface at that height, so the voxel (i, j, k) of a feature says "it
// shows in pixel (i, j) at layer k". Layer k >= 1 covers [slice_z(k - 1), slice_z(k)] with
// slice_z(k) = first + (k - 0.5) · height: grid z = (z - first) / height + 1.5 (the first layer's
// own thickness only shifts features below its slice, which get no support anyway).
struct LayerVoxels {
  VoxelGrid grid;
  double x0, y0, pixel, first, height;
  LayerVoxels(const PixelGrid& g, const OverhangRule& rule, double top)
      : x0(g.x0), y0(g.y0), pixel(g.pixel), first(rule.first_layer_height), height(rule.layer_height) {
    grid.cells = Eigen::Vector3i(g.nx, g.ny, static_cast<int>(std::max(0.0, layer(top))) + 2);
  }
  double layer(double z) const { return (z - first) / height + 1.5; }
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

// Faces less steep than the threshold, kept only where the slicer sees them. From one layer to
// the next a region of such faces reaches beyond the layer below by its own width w and then by
// what the faces around it add over the rest of the layer: the part's surface descends from the
// region over those faces (their mean horizontal run per height, cot s, length-weighted over the
// region's outline; walls add nothing), so the reach is w + (layer - w tan(slope)) cot s. The
// width of a region is 2 × area / outline of its projection (the width of a strip, the radius of a
// disc), which understates how far an irregular patch reaches; a region is dropped only when its
// reach stays under half of layer / tan(max slope): a lip or fold 0.1 mm wide on a wall (the
// slicer lays nothing under it), not a patch of a scan's surface just below the threshold among
// faces just above it (the slicer supports those: on the slimmed 70k-face bunny, dropping them
// cost 14% of the support). 1: overhang, 2: dense overhang (the reach past layer / tan(dense
// slope)), 0: neither; plus 4 on the region's edge (a side with no overhanging face).
std::vector<char> overhanging_faces(const Surface& s, const FaceAdjacency& adj, const OverhangRule& rule) {
  const int nf = static_cast<int>(s.F.rows());
  const double cos_max = std::cos(rule.max_slope_deg * M_PI / 180.0), cos_dense = std::cos(rule.dense_slope_deg * M_PI / 180.0);
  auto normal_of = [&](int f) -> Vec3 { return face_cross(s.V, s.F, f); };
  std::vector<char> kind(static_cast<size_t>(nf), 0);
  parallel_for(nf, [&](int f) {
    const Vec3 n = normal_of(f);
    const double len = n.norm();
    const double down = len > 0 ? -n.z() / len : 0.0;  // cos of the slope, for a face looking down
    kind[f] = down > cos_max ? (down > cos_dense ? 2 : 1) : 0;
  });
  // The overhanging faces in increasing order, each with a slot: their normals, neighbours and
  // regions are kept per slot (a few of the faces; the rest need none of it).
  std::vector<int> over, slot(static_cast<size_t>(nf), -1);
  for (int f = 0; f < nf; ++f)
    if (kind[f]) slot[f] = static_cast<int>(over.size()), over.push_back(f);
  const int no = static_cast<int>(over.size());
  std::vector<Vec3> normal(static_cast<size_t>(no));
  std::vector<std::array<int, 3>> across(static_cast<size_t>(no));
  parallel_for(no, [&](int i) {
    normal[i] = normal_of(over[i]);
    for (int k = 0; k < 3; ++k) across[i][k] = adj.across(over[i], k).face;
  });
  UnionFind regions(no);
  for (int i = 0; i < no; ++i)
    for (int k = 0; k < 3; ++k) {
      const int g = across[i][k];
      if (g >= 0 && kind[g]) regions.join(i, slot[g]);
    }
  // Per region (at its root): projected area, outline, sum of area × tan(slope), and along the
  // outline the length next to faces that look down or sideways, and that length × their cot.
  struct Region {
    double area = 0.0, outline = 0.0, area_tan = 0.0, side = 0.0, side_cot = 0.0;
  };
  std::vector<Region> region(static_cast<size_t>(no));
  for (int i = 0; i < no; ++i) {
    const int f = over[i];
    Region& r = region[regions.find(i)];
    const double flat = std::abs(normal[i].z()), steep = normal[i].head<2>().norm();
    r.area += 0.5 * flat;
    r.area_tan += 0.5 * steep;  // projected area × tan(slope) = half the normal's horizontal part
    for (int k = 0; k < 3; ++k) {
      const int g = across[i][k];
      if (g >= 0 && kind[g]) continue;
      const double length = (s.V.row(s.F(f, (k + 1) % 3)) - s.V.row(s.F(f, k))).head<2>().norm();
      r.outline += length;
      if (g < 0) continue;
      const Vec3 ng = normal_of(g);
      if (ng.z() > 0 || !(ng.head<2>().norm() > 0)) continue;
      r.side += length;
      r.side_cot += length * -ng.z() / ng.head<2>().norm();
    }
  }
  const double reach = rule.layer_height / std::tan(rule.max_slope_deg * M_PI / 180.0);
  const double reach_dense = rule.layer_height / std::tan(rule.dense_slope_deg * M_PI / 180.0);
  for (int i = 0; i < no; ++i) {
    const int f = over[i];
    const Region& r = region[regions.find(i)];
    double seen = INFINITY;
    if (r.outline > 0 && r.area > 0) {
      const double width = 2.0 * r.area / r.outline, tan_slope = r.area_tan / r.area;
      const double cot_around = r.side > 0 ? r.side_cot / r.side : 0.0;
      seen = width + std::max(0.0, rule.layer_height - width * tan_slope) * cot_around;
    }
    kind[f] = seen > 0.5 * reach ? (kind[f] == 2 && seen > reach_dense ? 2 : 1) : 0;
  }
  for (int i = 0; i < no; ++i) {  // on the edge of its region: a side with no overhanging face
    const int f = over[i];
    for (int k = 0; k < 3 && (kind[f] & 3); ++k) {
      const int g = across[i][k];
      if (g < 0 || !(kind[g] & 3)) kind[f] |= 4;
    }
  }
  return kind;
}

// Bottom creases and lowest vertices: the first slice of a keel or a tip is an island with nothing
// below it, which slicers support whatever the slope of the faces around it. The faces around each
// vertex (counting sort, no hashing) give every edge's other face. Faces [first, end) for the
// creases; vertices [first, end) for the tips.
void mark_creases(const Surface& s, const FaceAdjacency& adj, const OverhangRule& rule, const LayerVoxels& voxels,
                  Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) {
  const double cos_max_slope = std::cos(rule.max_slope_deg * M_PI / 180.0);
  const double cos2_max_slope = cos_max_slope * cos_max_slope;
  const double reach_overhang = 1.0 / std::tan(rule.max_slope_deg * M_PI / 180.0);
  const double reach_dense = 1.0 / std::tan(rule.dense_slope_deg * M_PI / 180.0);
  auto vertex = [&](int v) -> Vec3 { return s.V.row(v).transpose(); };
  // Each edge once, from its lower face index: asked first when the twins are a lookup (half the
  // edges then need no position at all), else after the cheaper tests.
  const bool twins_first = adj.has_every_twin();
  for (int f = static_cast<int>(first); f < end; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (twins_first && adj.across(f, k).face < f) continue;
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3), w = s.F(f, (k + 2) % 3);
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
      const FaceAdjacency::Twin twin = adj.across(f, k);
      if (twin.face < f) continue;
      const int x = twin.opposite;
      const Vec3 d = vertex(x), n1 = (b - a).cross(c - a), n2 = (a - b).cross(d - b);
      if (!rises_from(b, a, d) || !(n1.dot(d - a) < 0)) continue;
      const double reach = crease_reach(a, b, n1, n2);
      if (reach > reach_overhang) mark_feature(voxels, a, b, b, reach > reach_dense, out);
    }
  }
}

void mark_tips(const Surface& s, const FaceAdjacency& adj, const LayerVoxels& voxels, Eigen::Index first,
               Eigen::Index end, std::vector<PixelOverhang>& out) {
  for (int v = static_cast<int>(first); v < end; ++v) {
    if (adj.faces_end(v) - adj.faces_begin(v) < 3) continue;
    // Below every neighbour; most vertices have one no higher among their first face's.
    const double z = s.V(v, 2);
    bool lowest = true;
    for (const int* f = adj.faces_begin(v); f != adj.faces_end(v) && lowest; ++f)
      for (int u : adj.face(*f))
        if (u != v && !(z < s.V(u, 2))) lowest = false;
    if (!lowest) continue;
    const Vec3 p = s.V.row(v);
    mark_feature(voxels, p, p, p, true, out);
  }
}

// The overhanging faces [first, end) (kind: overhanging_faces()) marked, and those on a region's
// edge also shifted by the reach both ways along their level direction: the slicer grows each
// layer's overhang back by one layer's reach into the layer around it, so where an overhang region
// ends along the part's outline its contact runs on that far into the steeper faces beside it.
void mark_overhangs(const Surface& s, const std::vector<char>& kind, const OverhangRule& rule, const LayerVoxels& voxels,
                    Eigen::Index first, Eigen::Index end, std::vector<PixelOverhang>& out) {
  const double reach = rule.layer_height / std::tan(rule.max_slope_deg * M_PI / 180.0);
  for (int f = static_cast<int>(first); f < end; ++f) {
    if (!kind[f]) continue;
    const Vec3 a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const bool dense = (kind[f] & 3) == 2;
    mark_feature(voxels, a, b, c, dense, out);
    const Vec3 n = (b - a).cross(c - a);
    if (!(kind[f] & 4) || !(n.head<2>().norm() > 0)) continue;
    const Vec3 along = Vec3(-n.y(), n.x(), 0.0).normalized() * reach;  // the face's level direction
    for (double side : {-1.0, 1.0}) mark_feature(voxels, a + side * along, b + side * along, c + side * along, dense, out);
  }
}

}  // namespace

SupportRaster build_support_raster(const Surface& s, const PixelGrid& g, const OverhangRule& rule) {
  return build_support_raster(s, FaceAdjacency(s), g, rule);
}

SupportRaster build_support_raster(const Surface& s, const FaceAdjacency& adj, const PixelGrid& g, const OverhangRule& rule) {
  if (!(g.pixel > 0) || g.nx <= 0 || g.ny <= 0) throw std::invalid_argument("support raster: empty pixel grid");
  if (!(rule.max_slope_deg > 0 && rule.max_slope_deg <= 90))
    throw std::invalid_argument("support raster: the overhang slope must lie in (0, 90] degrees");
  SupportRaster out;
  out.grid = g;
  if (rule.slices) rasterize_slices(s, adj, rule, out);
  else rasterize_solid(s, g, out);
  const LayerVoxels voxels(g, rule, s.V.col(2).maxCoeff());
  const std::vector<char> kind = overhanging_faces(s, adj, rule);
  using Part = std::vector<PixelOverhang>;
  const Part faces = gather_in_ranges<PixelOverhang>(
      s.F.rows(), [&](Eigen::Index a, Eigen::Index b, Part& part) { mark_overhangs(s, kind, rule, voxels, a, b, part); });
  out.overhangs.insert(out.overhangs.end(), faces.begin(), faces.end());
  for (const Part& more :
       {rule.creases ? gather_in_ranges<PixelOverhang>(
                           s.F.rows(), [&](Eigen::Index a, Eigen::Index b, Part& part) { mark_creases(s, adj, rule, voxels, a, b, part); })
                     : Part{},
        rule.tips ? gather_in_ranges<PixelOverhang>(
                        s.V.rows(), [&](Eigen::Index a, Eigen::Index b, Part& part) { mark_tips(s, adj, voxels, a, b, part); })
                  : Part{}})
    out.overhangs.insert(out.overhangs.end(), more.begin(), more.end());
  sort_by_pixel(out.overhangs, g.count(), [](const PixelOverhang& x, const PixelOverhang& y) {
    if (x.layer_low != y.layer_low) return x.layer_low < y.layer_low;
    if (x.layer_high != y.layer_high) return x.layer_high < y.layer_high;
    return x.dense < y.dense;
  });
  return out;
}

}  // namespace slim
