#include "core/support_model/support_raster.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/geometry/face_adjacency.h"
#include "core/platform/parallel_for.h"
#include "core/support_model/overhang_features.h"
#include "core/support_model/slice_raster.h"

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
  const std::vector<PixelOverhang> features = overhang_features(s, adj, g, rule);
  out.overhangs.insert(out.overhangs.end(), features.begin(), features.end());
  sort_by_pixel(out.overhangs, g.count(), [](const PixelOverhang& x, const PixelOverhang& y) {
    if (x.layer_low != y.layer_low) return x.layer_low < y.layer_low;
    if (x.layer_high != y.layer_high) return x.layer_high < y.layer_high;
    return x.dense < y.dense;
  });
  return out;
}

}  // namespace slim
