#include "core/slice_raster.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/layer_slices.h"
#include "core/parallel_for.h"

namespace slim {
namespace {

struct RowCrossing {
  int row;
  double x;
  int winding;
  bool operator<(const RowCrossing& o) const { return row != o.row ? row < o.row : x < o.x; }
};

// The pixel centres that closed polylines wind around (nonzero rule), as 0/1 per pixel. Each
// polyline's last point joins its first. A centre exactly on an edge going up or down counts on one
// side only (edges are half-open in y), so polygons that share an edge tile without gap or overlap.
void fill_pixels(const std::vector<const Polyline2*>& polygons, const PixelGrid& g, char* pixels) {
  std::vector<RowCrossing> crossings;
  for (const Polyline2* poly : polygons) {
    const size_t n = poly->size();
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& p = (*poly)[i];
      const Eigen::Vector2d& q = (*poly)[(i + 1) % n];
      if (p.y() == q.y()) continue;
      const double lo = std::min(p.y(), q.y()), hi = std::max(p.y(), q.y());
      const int row0 = std::max(0, static_cast<int>(std::ceil((lo - g.y0) / g.pixel - 0.5)));
      const int row1 = std::min(g.ny - 1, static_cast<int>(std::ceil((hi - g.y0) / g.pixel - 0.5)));
      for (int row = row0; row <= row1; ++row) {
        const double y = g.y0 + (row + 0.5) * g.pixel;
        if ((p.y() <= y) == (q.y() <= y)) continue;
        const double x = p.x() + (y - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
        crossings.push_back({row, x, q.y() > p.y() ? -1 : 1});
      }
    }
  }
  std::sort(crossings.begin(), crossings.end());
  for (size_t c = 0; c < crossings.size();) {
    const int row = crossings[c].row;
    int winding = 0;
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x0 + (i + 0.5) * g.pixel;
      for (; c < crossings.size() && crossings[c].row == row && crossings[c].x < x; ++c) winding += crossings[c].winding;
      pixels[i + g.nx * row] = winding != 0;
    }
    while (c < crossings.size() && crossings[c].row == row) ++c;  // beyond the last centre
  }
}

std::vector<const Polyline2*> pointers(const std::vector<Polyline2>& a, const std::vector<Polyline2>* b = nullptr) {
  std::vector<const Polyline2*> out;
  for (const Polyline2& p : a) out.push_back(&p);
  if (b)
    for (const Polyline2& p : *b) out.push_back(&p);
  return out;
}

}  // namespace

void rasterize_slices(const Surface& s, const FaceAdjacency& adj, const OverhangRule& rule, SupportRaster& out) {
  const PixelGrid& g = out.grid;
  const double first = rule.first_layer_height, layer = rule.layer_height;
  if (!(first > 0) || !(layer > 0)) throw std::invalid_argument("slice raster: layer heights must be positive");
  auto slice_z = [&](int k) { return k <= 0 ? 0.5 * first : first + (k - 0.5) * layer; };
  const double top = s.V.col(2).maxCoeff();
  std::vector<double> heights;
  for (int k = 0; slice_z(k) <= top; ++k) heights.push_back(slice_z(k));
  const std::vector<LayerSlice> slices = slice_layers(s, adj, heights, rule.slice_max_gap);
  const int layers = static_cast<int>(heights.size()), n = g.count();
  // Per slice: the pixels it fills, and where it lost chains, the pixels it would fill with them.
  std::vector<char> solid(static_cast<size_t>(layers) * n, 0), with_lost(solid.size(), 0);
  parallel_for(layers, [&](int k) {
    const size_t at = static_cast<size_t>(k) * n;
    fill_pixels(pointers(slices[k].loops), g, solid.data() + at);
    if (!slices[k].dropped.empty()) fill_pixels(pointers(slices[k].loops, &slices[k].dropped), g, with_lost.data() + at);
  });
  out.span_begin.assign(static_cast<size_t>(n) + 1, 0);
  out.spans.clear();
  for (int p = 0; p < n; ++p) {
    out.span_begin[p] = static_cast<int>(out.spans.size());
    for (int k = 0; k < layers;) {
      if (!solid[static_cast<size_t>(k) * n + p]) {
        ++k;
        continue;
      }
      const int k0 = k;
      while (k < layers && solid[static_cast<size_t>(k) * n + p]) ++k;
      out.spans.push_back({slice_z(k0) - 0.25 * layer, slice_z(k - 1) + 0.25 * layer});
    }
    for (int k = 1; k < layers; ++k) {
      const size_t here = static_cast<size_t>(k) * n + p, below = here - n;
      if (slices[k - 1].dropped.empty() || !solid[here] || solid[below] || !with_lost[below]) continue;
      out.overhangs.push_back({p, k, k, true});
    }
  }
  out.span_begin[n] = static_cast<int>(out.spans.size());
}

}  // namespace slim
