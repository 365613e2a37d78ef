#include "core/support_model/slice_raster.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/platform/parallel_for.h"
#include "core/support_model/layer_slices.h"

namespace slim {
namespace {

struct RowCrossing {
  int row;
  double x;
  int winding;
  bool operator<(const RowCrossing& o) const { return row != o.row ? row < o.row : x < o.x; }
};

// The pixel centres that closed polylines wind around (nonzero rule), as 0/1 per pixel of the rows
// the polylines cross (the caller clears the others). Each
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
  // The slices in blocks of layers, filled in parallel: per slice the pixels it fills, and where it
  // lost chains, the pixels it would fill with them. The memory is a block's, whatever the height.
  constexpr int kBlock = 32;
  std::vector<char> solid(static_cast<size_t>(kBlock + 1) * n, 0), with_lost(solid.size(), 0);  // row 0: the layer below
  struct Run {
    int pixel, k0, k1;
  };
  std::vector<Run> runs;
  std::vector<int> run_start(static_cast<size_t>(n), -1);
  for (int k0 = 0; k0 < layers; k0 += kBlock) {
    const int count = std::min(kBlock, layers - k0);
    if (k0 > 0) {  // the last layer of the previous block becomes the layer below
      std::copy_n(solid.begin() + static_cast<ptrdiff_t>(kBlock) * n, n, solid.begin());
      std::copy_n(with_lost.begin() + static_cast<ptrdiff_t>(kBlock) * n, n, with_lost.begin());
    }
    parallel_for(count, [&](int i) {
      const size_t at = static_cast<size_t>(i + 1) * n;
      const LayerSlice& slice = slices[static_cast<size_t>(k0 + i)];
      std::fill_n(solid.begin() + static_cast<ptrdiff_t>(at), n, 0);
      fill_pixels(pointers(slice.loops), g, solid.data() + at);
      if (slice.dropped.empty()) return;
      std::fill_n(with_lost.begin() + static_cast<ptrdiff_t>(at), n, 0);
      fill_pixels(pointers(slice.loops, &slice.dropped), g, with_lost.data() + at);
    });
    for (int i = 0; i < count; ++i) {
      const int k = k0 + i;
      const char* here = solid.data() + static_cast<size_t>(i + 1) * n;
      const char* below = solid.data() + static_cast<size_t>(i) * n;
      const char* below_with_lost = with_lost.data() + static_cast<size_t>(i) * n;
      const bool lost_below = k > 0 && !slices[static_cast<size_t>(k - 1)].dropped.empty();
      for (int p = 0; p < n; ++p) {
        int& start = run_start[static_cast<size_t>(p)];
        if (here[p] && start < 0) start = k;
        if (!here[p] && start >= 0) runs.push_back({p, start, k - 1}), start = -1;
        if (lost_below && here[p] && !below[p] && below_with_lost[p]) out.overhangs.push_back({p, k, k, true});
      }
    }
  }
  for (int p = 0; p < n; ++p)
    if (run_start[static_cast<size_t>(p)] >= 0) runs.push_back({p, run_start[static_cast<size_t>(p)], layers - 1});
  // The runs by pixel (a stable counting sort: each pixel's runs stay in upward order).
  out.span_begin.assign(static_cast<size_t>(n) + 1, 0);
  for (const Run& r : runs) ++out.span_begin[static_cast<size_t>(r.pixel) + 1];
  for (int p = 0; p < n; ++p) out.span_begin[p + 1] += out.span_begin[p];
  out.spans.assign(runs.size(), SolidSpan{});
  std::vector<int> fill(out.span_begin.begin(), out.span_begin.end() - 1);
  for (const Run& r : runs)
    out.spans[static_cast<size_t>(fill[static_cast<size_t>(r.pixel)]++)] = {slice_z(r.k0) - 0.25 * layer, slice_z(r.k1) + 0.25 * layer};
}

}  // namespace slim
