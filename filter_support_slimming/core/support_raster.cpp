#include "core/support_raster.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <Eigen/Geometry>

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
void mark_segment(const Vec3& a, const Vec3& b, const PixelGrid& g, std::vector<PixelOverhang>& out) {
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
      out.push_back({i + g.nx * j, std::min(za, zb), std::max(za, zb), true});
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

// Bottom creases and lowest vertices: the first slice of a keel or a tip is an island with nothing
// below it, which slicers support whatever the slope of the faces around it. The faces around each
// vertex (counting sort, no hashing) give every edge's other face.
void mark_creases_and_tips(const Surface& s, double cos_max_slope, const PixelGrid& g, std::vector<PixelOverhang>& out) {
  const int nv = static_cast<int>(s.V.rows()), nf = static_cast<int>(s.F.rows());
  std::vector<int> begin(static_cast<size_t>(nv) + 1, 0), around(static_cast<size_t>(3) * nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) ++begin[s.F(f, k) + 1];
  for (int v = 0; v < nv; ++v) begin[v + 1] += begin[v];
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) around[fill[s.F(f, k)]++] = f;
  auto vertex = [&](int v) -> Vec3 { return s.V.row(v).transpose(); };
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3), w = s.F(f, (k + 2) % 3);
      const Vec3 a = vertex(u), b = vertex(v), c = vertex(w), e = b - a;
      const double len = e.norm();
      // The edge less steep than the threshold (cos of its slope = |e.xy| / |e| > cos(max slope)),
      // and this face rising away from it.
      if (!(len > 0) || !(e.head<2>().norm() / len > cos_max_slope) || !rises_from(a, b, c)) continue;
      int twin = -1, x = -1, seen = 0;
      for (int i = begin[u]; i < begin[u + 1]; ++i) {
        const int h = around[i];
        for (int m = 0; m < 3; ++m)
          if (s.F(h, m) == v && s.F(h, (m + 1) % 3) == u) twin = h, x = s.F(h, (m + 2) % 3), ++seen;
        for (int m = 0; m < 3 && h != f; ++m)
          if (s.F(h, m) == u && s.F(h, (m + 1) % 3) == v) seen += 2;  // a third face: not manifold
      }
      // Once per edge (from its lower face index), manifold, the twin rising too, and convex: the
      // twin's third vertex behind this face's plane.
      if (seen != 1 || twin < f) continue;
      const Vec3 d = vertex(x);
      if (rises_from(b, a, d) && (b - a).cross(c - a).dot(d - a) < 0) mark_segment(a, b, g, out);
    }
  }
  for (int v = 0; v < nv; ++v) {
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
  const double cos_max = std::cos(rule.max_slope_deg * M_PI / 180.0);
  const double cos_dense = std::cos(rule.dense_slope_deg * M_PI / 180.0);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Vec3 a = s.V.row(s.F(f, 0)).transpose(), b = s.V.row(s.F(f, 1)).transpose(), c = s.V.row(s.F(f, 2)).transpose();
    const Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    if (!(len > 0)) continue;
    const double down = -n.z() / len;  // cos of the slope from the horizontal, for a face looking down
    if (down > cos_max) mark_triangle(a, b, c, down > cos_dense, g, out.overhangs);
  }
  mark_creases_and_tips(s, cos_max, g, out.overhangs);
  sort_by_pixel(out.overhangs, g.count(), [](const PixelOverhang& x, const PixelOverhang& y) {
    if (x.z_low != y.z_low) return x.z_low < y.z_low;
    if (x.z_high != y.z_high) return x.z_high < y.z_high;
    return x.dense < y.dense;
  });
  return out;
}

}  // namespace slim
