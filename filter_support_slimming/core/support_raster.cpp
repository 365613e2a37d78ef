#include "core/support_raster.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <Eigen/Geometry>

#include "core/face_adjacency.h"

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

// Pixel index range [lo, hi] of pixel centres (centres = true) or squares (false) that a 1D extent
// [a, b] reaches, clamped to [0, n - 1]; lo > hi when none.
void pixel_range(double a, double b, double origin, double pixel, int n, bool centres, int& lo, int& hi) {
  const double u = (a - origin) / pixel, v = (b - origin) / pixel;
  // Squares are closed: an extent ending exactly on a pixel boundary touches both pixels.
  const double l = centres ? std::ceil(u - 0.5) : std::ceil(u) - 1.0;
  const double h = centres ? std::floor(v - 0.5) : std::floor(v);
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
  for (int p = 0; p < pixels; ++p)
    if (begin[p + 1] - begin[p] > 1) std::sort(sorted.begin() + begin[p], sorted.begin() + begin[p + 1], less);
  items.swap(sorted);
}

// The solid spans: every face crossed by the rays through the pixel centres, then nonzero winding
// along each ray.
void rasterize_solid(const Surface& s, const PixelGrid& g, SupportRaster& out) {
  std::vector<Crossing> crossings;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const int id[3] = {s.F(f, 0), s.F(f, 1), s.F(f, 2)};
    const Vec3 p[3] = {s.V.row(id[0]).transpose(), s.V.row(id[1]).transpose(), s.V.row(id[2]).transpose()};
    const Vec2 q[3] = {p[0].head<2>(), p[1].head<2>(), p[2].head<2>()};
    const double area2 = cross2(q[1] - q[0], q[2] - q[0]);
    if (!(std::abs(area2) > 0)) continue;  // seen edge on: no ray crosses it
    const int orient = area2 > 0 ? 1 : -1;  // +1: counter-clockwise from above, looking up
    int i0, i1, j0, j1;
    pixel_range(std::min({q[0].x(), q[1].x(), q[2].x()}), std::max({q[0].x(), q[1].x(), q[2].x()}), g.x0, g.pixel, g.nx, true, i0, i1);
    pixel_range(std::min({q[0].y(), q[1].y(), q[2].y()}), std::max({q[0].y(), q[1].y(), q[2].y()}), g.y0, g.pixel, g.ny, true, j0, j1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const Vec2 c(g.x0 + (i + 0.5) * g.pixel, g.y0 + (j + 0.5) * g.pixel);
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k)
          inside = edge_side(q[k], id[k], q[(k + 1) % 3], id[(k + 1) % 3], c) == orient;
        if (!inside) continue;
        const double w0 = cross2(q[1] - c, q[2] - c), w1 = cross2(q[2] - c, q[0] - c);
        const double z = (w0 * p[0].z() + w1 * p[1].z() + (area2 - w0 - w1) * p[2].z()) / area2;
        crossings.push_back({i + g.nx * j, z, -orient});
      }
    }
  }
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

// Marks every pixel whose square the triangle (a, b, c) overlaps (separating axes: the pixel
// range covers the bounding box, the edge functions the rest) with the triangle's z range there.
void mark_triangle(const Vec3& a, const Vec3& b, const Vec3& c, bool dense, const PixelGrid& g,
                   std::vector<PixelOverhang>& out) {
  const Vec2 q[3] = {a.head<2>(), b.head<2>(), c.head<2>()};
  double area2 = cross2(q[1] - q[0], q[2] - q[0]);
  if (!(std::abs(area2) > 0)) return;
  const double orient = area2 > 0 ? 1.0 : -1.0;
  // z = a.z + gx (x - a.x) + gy (y - a.y) over the triangle's plane.
  const Vec2 e1 = q[1] - q[0], e2 = q[2] - q[0];
  const double gx = ((b.z() - a.z()) * e2.y() - (c.z() - a.z()) * e1.y()) / area2;
  const double gy = ((c.z() - a.z()) * e1.x() - (b.z() - a.z()) * e2.x()) / area2;
  const double zmin = std::min({a.z(), b.z(), c.z()}), zmax = std::max({a.z(), b.z(), c.z()});
  int i0, i1, j0, j1;
  pixel_range(std::min({q[0].x(), q[1].x(), q[2].x()}), std::max({q[0].x(), q[1].x(), q[2].x()}), g.x0, g.pixel, g.nx, false, i0, i1);
  pixel_range(std::min({q[0].y(), q[1].y(), q[2].y()}), std::max({q[0].y(), q[1].y(), q[2].y()}), g.y0, g.pixel, g.ny, false, j0, j1);
  const double half = 0.5 * g.pixel, slope = (std::abs(gx) + std::abs(gy)) * half;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const Vec2 centre(g.x0 + (i + 0.5) * g.pixel, g.y0 + (j + 0.5) * g.pixel);
      bool overlaps = true;
      for (int k = 0; k < 3 && overlaps; ++k) {
        const Vec2 e = q[(k + 1) % 3] - q[k];
        // The largest edge function over the square's corners: at the centre plus the half-extent
        // along the edge's normal, |e.x| + |e.y| times half a pixel.
        const double best = orient * cross2(e, centre - q[k]) + (std::abs(e.x()) + std::abs(e.y())) * half;
        overlaps = best >= 0;
      }
      if (!overlaps) continue;
      const double zc = a.z() + gx * (centre.x() - a.x()) + gy * (centre.y() - a.y());
      out.push_back({i + g.nx * j, std::max(zmin, zc - slope), std::min(zmax, zc + slope), dense});
    }
  }
}

// Marks every pixel whose square the segment a-b crosses, with the segment's z range inside it
// (Liang-Barsky clipping of the segment to the square).
void mark_segment(const Vec3& a, const Vec3& b, bool dense, const PixelGrid& g, std::vector<PixelOverhang>& out) {
  int i0, i1, j0, j1;
  pixel_range(std::min(a.x(), b.x()), std::max(a.x(), b.x()), g.x0, g.pixel, g.nx, false, i0, i1);
  pixel_range(std::min(a.y(), b.y()), std::max(a.y(), b.y()), g.y0, g.pixel, g.ny, false, j0, j1);
  const Vec3 d = b - a;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const double lo[2] = {g.x0 + i * g.pixel, g.y0 + j * g.pixel};
      double t0 = 0.0, t1 = 1.0;
      for (int axis = 0; axis < 2 && t0 <= t1; ++axis) {
        const double o = a[axis], v = d[axis], l = lo[axis], h = lo[axis] + g.pixel;
        if (v == 0) {
          if (o < l || o > h) t1 = -1.0;
          continue;
        }
        double ta = (l - o) / v, tb = (h - o) / v;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      if (t0 > t1) continue;
      const double za = a.z() + t0 * d.z(), zb = a.z() + t1 * d.z();
      out.push_back({i + g.nx * j, std::min(za, zb), std::max(za, zb), dense});
    }
  }
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
// where the crease meets the layer, the wedge {x : (x - tip)·m_i <= 0} (m_i the faces' outward
// normals in the plane); one layer up the tip has moved uphill along the crease by
// layer / tan(crease slope); the reach is the new tip's distance from the old wedge. The slicer
// sees an overhang when it exceeds layer / tan(max slope), a dense one beyond layer / tan(dense
// slope). A level crease appears all at once: infinite. 0 when the tip stays inside.
double crease_reach(const Vec3& a, const Vec3& b, const Vec3& n1, const Vec3& n2) {
  const Vec2 m1 = n1.head<2>(), m2 = n2.head<2>();
  if (!(m1.norm() > 0) || !(m2.norm() > 0)) return 0.0;  // a level face: its own rule covers it
  const Vec3 e = b.z() >= a.z() ? Vec3(b - a) : Vec3(a - b);
  if (!(e.z() > 0)) return INFINITY;
  const Vec2 tip = e.head<2>() / e.z();  // one unit of height up the crease
  const Vec2 w[2] = {m1.normalized(), m2.normalized()};
  double distance = tip.norm();  // to the old corner
  for (int i = 0; i < 2; ++i) {
    const double out = tip.dot(w[i]);
    const Vec2 foot = tip - out * w[i];  // on the old wedge's side i, if inside the other half-plane
    if (out > 0 && foot.dot(w[1 - i]) <= 1e-12) distance = std::min(distance, out);
    if (out <= 0 && tip.dot(w[1 - i]) <= 0) return 0.0;  // the tip stays inside the old slice
  }
  return distance;
}

// Faces less steep than the threshold, kept only in connected regions wide enough for the slicer
// to see them: layer by layer a region reaches at most its own width beyond the layer below (a lip
// or fold 0.1 mm wide never passes layer / tan(max slope)). The width of a region is measured as
// 2 × area / outline of its projection (the width of a strip, the radius of a disc). 1: overhang,
// 2: dense overhang (the same test against layer / tan(dense slope)), 0: neither.
std::vector<char> overhanging_faces(const Surface& s, const FaceAdjacency& adj, const OverhangRule& rule) {
  const int nf = static_cast<int>(s.F.rows());
  const double cos_max = std::cos(rule.max_slope_deg * M_PI / 180.0), cos_dense = std::cos(rule.dense_slope_deg * M_PI / 180.0);
  std::vector<char> kind(static_cast<size_t>(nf), 0);
  std::vector<int> parent(static_cast<size_t>(nf));
  auto root = [&](int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  for (int f = 0; f < nf; ++f) {
    parent[f] = f;
    const Vec3 a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    const double down = len > 0 ? -n.z() / len : 0.0;  // cos of the slope, for a face looking down
    kind[f] = down > cos_max ? (down > cos_dense ? 2 : 1) : 0;
  }
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3 && kind[f]; ++k) {
      const int g = adj.across[3 * f + k];
      if (g >= 0 && kind[g]) parent[root(f)] = root(g);  // deterministic: no ranks, fixed order
    }
  std::vector<double> area(static_cast<size_t>(nf), 0.0), outline(static_cast<size_t>(nf), 0.0);
  for (int f = 0; f < nf; ++f) {
    if (!kind[f]) continue;
    const int r = root(f);
    const Vec3 a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    area[r] += 0.5 * std::abs(cross2((b - a).head<2>(), (c - a).head<2>()));
    for (int k = 0; k < 3; ++k) {
      const int g = adj.across[3 * f + k];
      if (g < 0 || !kind[g])
        outline[r] += (s.V.row(s.F(f, (k + 1) % 3)) - s.V.row(s.F(f, k))).head<2>().norm();
    }
  }
  const double reach = rule.layer_height / std::tan(rule.max_slope_deg * M_PI / 180.0);
  const double reach_dense = rule.layer_height / std::tan(rule.dense_slope_deg * M_PI / 180.0);
  for (int f = 0; f < nf; ++f) {
    if (!kind[f]) continue;
    const int r = root(f);
    const double width = outline[r] > 0 ? 2.0 * area[r] / outline[r] : INFINITY;
    kind[f] = width > reach ? (kind[f] == 2 && width > reach_dense ? 2 : 1) : 0;
  }
  return kind;
}

// Bottom creases and lowest vertices: the first slice of a keel or a tip is an island with nothing
// below it, which slicers support whatever the slope of the faces around it. The faces around each
// vertex (counting sort, no hashing) give every edge's other face.
void mark_creases_and_tips(const Surface& s, const FaceAdjacency& adj, const OverhangRule& rule, const PixelGrid& g,
                           std::vector<PixelOverhang>& out) {
  const double cos_max_slope = std::cos(rule.max_slope_deg * M_PI / 180.0);
  const double reach_overhang = 1.0 / std::tan(rule.max_slope_deg * M_PI / 180.0);
  const double reach_dense = 1.0 / std::tan(rule.dense_slope_deg * M_PI / 180.0);
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  const std::vector<int>& begin = adj.vertex_begin;
  const std::vector<int>& around = adj.vertex_face;
  auto vertex = [&](int v) -> Vec3 { return s.V.row(v).transpose(); };
  for (int f = 0; f < nf && rule.creases; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3), w = s.F(f, (k + 2) % 3);
      const Vec3 a = vertex(u), b = vertex(v), c = vertex(w), e = b - a;
      const double len = e.norm();
      // The edge less steep than the threshold (cos of its slope = |e.xy| / |e| > cos(max slope)),
      // and this face rising away from it.
      if (!(len > 0) || !(e.head<2>().norm() / len > cos_max_slope) || !rises_from(a, b, c)) continue;
      // Once per edge (from its lower face index), manifold, the other face rising too, and convex:
      // the other face's third vertex behind this face's plane.
      const int twin = adj.across[3 * f + k];
      if (twin < f) continue;
      int x = -1;
      for (int m = 0; m < 3; ++m)
        if (s.F(twin, m) != u && s.F(twin, m) != v) x = s.F(twin, m);
      const Vec3 d = vertex(x), n1 = (b - a).cross(c - a), n2 = (a - b).cross(d - b);
      if (!rises_from(b, a, d) || !(n1.dot(d - a) < 0)) continue;
      const double reach = crease_reach(a, b, n1, n2);
      if (reach > reach_overhang) mark_segment(a, b, reach > reach_dense, g, out);
    }
  }
  for (int v = 0; v < nv && rule.tips; ++v) {
    if (begin[v + 1] - begin[v] < 3) continue;
    double lowest = INFINITY;
    for (int i = begin[v]; i < begin[v + 1]; ++i)
      for (int m = 0; m < 3; ++m)
        if (s.F(around[i], m) != v) lowest = std::min(lowest, s.V(s.F(around[i], m), 2));
    if (!(s.V(v, 2) < lowest)) continue;
    const double i = std::floor((s.V(v, 0) - g.x0) / g.pixel), j = std::floor((s.V(v, 1) - g.y0) / g.pixel);
    if (i >= 0 && j >= 0 && i < g.nx && j < g.ny)
      out.push_back({static_cast<int>(i) + g.nx * static_cast<int>(j), s.V(v, 2), s.V(v, 2), true});
  }
}

}  // namespace

SupportRaster build_support_raster(const Surface& s, const PixelGrid& g, const OverhangRule& rule) {
  if (!(g.pixel > 0) || g.nx <= 0 || g.ny <= 0) throw std::invalid_argument("support raster: empty pixel grid");
  if (!(rule.max_slope_deg > 0 && rule.max_slope_deg <= 90))
    throw std::invalid_argument("support raster: the overhang slope must lie in (0, 90] degrees");
  SupportRaster out;
  out.grid = g;
  rasterize_solid(s, g, out);
  const FaceAdjacency adj = face_adjacency(s);
  const std::vector<char> kind = overhanging_faces(s, adj, rule);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (kind[f]) mark_triangle(s.V.row(s.F(f, 0)), s.V.row(s.F(f, 1)), s.V.row(s.F(f, 2)), kind[f] == 2, g, out.overhangs);
  mark_creases_and_tips(s, adj, rule, g, out.overhangs);
  sort_by_pixel(out.overhangs, g.count(), [](const PixelOverhang& x, const PixelOverhang& y) {
    if (x.z_low != y.z_low) return x.z_low < y.z_low;
    if (x.z_high != y.z_high) return x.z_high < y.z_high;
    return x.dense < y.dense;
  });
  return out;
}

}  // namespace slim
