#include "core/support_model/support_sweep.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace slim {
namespace {

using Range = std::pair<int, int>;  // [lo, hi] layers, inclusive

// Appends [lo, hi] to sorted, disjoint ranges, merging it with the last when they touch.
void append_merged(std::vector<Range>& out, int lo, int hi) {
  if (lo > hi) return;
  if (!out.empty() && lo <= out.back().second + 1) out.back().second = std::max(out.back().second, hi);
  else out.push_back({lo, hi});
}

// a minus b, both sorted and disjoint.
void subtract(const Range* a, const Range* a_end, const Range* b, const Range* b_end, std::vector<Range>& out) {
  out.clear();
  for (; a != a_end; ++a) {
    int lo = a->first;
    for (const Range* c = b; c != b_end && lo <= a->second; ++c) {
      if (c->second < lo) continue;
      if (c->first > a->second) break;
      if (c->first > lo) out.push_back({lo, c->first - 1});
      lo = std::max(lo, c->second + 1);
    }
    if (lo <= a->second) out.push_back({lo, a->second});
  }
}

// a ∩ b, both sorted and disjoint.
void intersect(const Range* a, const Range* a_end, const Range* b, const Range* b_end, std::vector<Range>& out) {
  out.clear();
  while (a != a_end && b != b_end) {
    const int lo = std::max(a->first, b->first), hi = std::min(a->second, b->second);
    if (lo <= hi) out.push_back({lo, hi});
    if (a->second < b->second) ++a;
    else ++b;
  }
}

bool covers(const std::vector<Range>& ranges, int k) {
  for (const Range& r : ranges)
    if (r.first <= k && k <= r.second) return true;
  return false;
}

// Whether the part fills pixel p at the slice of layer k (a span of the raster holds its height).
bool fills(const SupportRaster& raster, int p, double slice_z) {
  for (int s = raster.span_begin[p]; s < raster.span_begin[p + 1]; ++s)
    if (raster.spans[s].bottom <= slice_z && slice_z <= raster.spans[s].top) return true;
  return false;
}

// Whether pixel p lies inside the part at layer k: filled, and so are its four neighbours (beyond
// the raster is free). The slicer rasterises a contact with any coverage and masks a pixel only
// inside the part eroded by one pixel, so a contact on the part's outline still reaches its cell.
bool inside_part(const SupportRaster& raster, const SlicerLayers& layers, int p, int k) {
  const PixelGrid& g = raster.grid;
  const int i = p % g.nx, j = p / g.nx;
  if (i == 0 || j == 0 || i + 1 == g.nx || j + 1 == g.ny) return false;
  const double z = layers.slice_z(k);
  for (int q : {p, p - 1, p + 1, p - g.nx, p + g.nx})
    if (!fills(raster, q, z)) return false;
  return true;
}

}  // namespace

int SlicerLayers::first_slice_at_or_above(double z) const {
  if (count <= 0 || z <= slice_z(0)) return 0;
  int k = static_cast<int>(std::max(1.0, std::min(static_cast<double>(count), std::ceil((z - first_height) / height + 0.5))));
  while (k > 1 && slice_z(k - 1) >= z) --k;
  while (k < count && slice_z(k) < z) ++k;
  return k;
}

int SlicerLayers::last_slice_at_or_below(double z) const {
  if (count <= 0 || z < slice_z(0)) return -1;
  int k = static_cast<int>(std::max(0.0, std::min(static_cast<double>(count - 1), std::floor((z - first_height) / height + 0.5))));
  while (k + 1 < count && slice_z(k + 1) <= z) ++k;
  while (k > 0 && slice_z(k) > z) --k;
  return k;
}

namespace {

using RawEvent = GridSupportSweep::RawEvent;

// Events of a range of layers [lo, hi]: counted from hi down to lo, as the sweep goes down.
void add_range(std::vector<RawEvent>& raw, int pixel, const Range& r, GridSupportSweep::Kind kind) {
  raw.push_back({r.second, {pixel, kind, 1}});
  if (r.first > 0) raw.push_back({r.first - 1, {pixel, kind, -1}});
}

}  // namespace

SweepRates sweep_rates(const GridSweepSettings& s, const SlicerLayers& layers, double t) {
  auto spacing = [&](double height) { return s.extrusion_width - height * (1.0 - M_PI / 4.0); };
  const double at_t = spacing(t), at_layer = spacing(layers.height), at_first = spacing(layers.first_height);
  SweepRates r;
  r.line_per_mm2 = at_t;
  // The island's outline lies half a line spacing past the cells, less half a width (a closing);
  // the fill area is 0.4 spacings inside it, and its lines stop half a spacing short of that.
  r.fill_end = 0.5 * s.extrusion_width + 0.4 * at_layer;
  r.interface_per_mm3 = at_t / at_layer;   // dense: one line per line spacing
  r.interface_depth = s.interface_layers * t / layers.height;
  // A landing: a bridging contact layer (round lines of the nozzle's diameter, a line spacing
  // apart) and interface_layers - 1 dense layers, where the fill would stand otherwise.
  if (s.interface_layers > 0) {
    const double bridge = M_PI / 4.0 * s.nozzle_diameter * s.nozzle_diameter / at_layer;
    const double below = s.interface_layers - 1.0;
    r.bottom_interface_per_mm2 =
        std::max(0.0, bridge + below * t * r.interface_per_mm3 - (s.nozzle_diameter + below * t) * at_t / s.grid_spacing);
  }
  r.first_fill_per_mm2 = s.first_layer_density * layers.first_height;
  r.first_sheath_per_mm = layers.first_height * at_first;
  r.first_inset = 0.4 * at_first;
  return r;
}

std::vector<double> support_layer_thickness(const std::vector<char>& has_contact, const SlicerLayers& layers, double max_height) {
  const int count = layers.count;
  std::vector<double> out(static_cast<size_t>(count), layers.height);
  if (count > 0) out[0] = layers.first_height;
  int below = 0;  // the layer whose top the current gap starts from
  for (int j = 1; j < count; ++j) {
    if (!has_contact[j]) continue;
    const double gap = layers.print_z(j) - layers.print_z(below);
    const double step = gap / std::max(1.0, std::ceil(gap / max_height - 1e-9));
    for (int i = below + 1; i <= j; ++i) out[i] = step;
    below = j;
  }
  return out;
}

// Per pixel, in object layers: what the part fills (handed to block_events, which finds what
// stops a column), what trims a support layer there (the part within contact_distance above or
// below), the part's top layers, and the contacts (the support layer under each overhang).
void GridSupportSweep::pixel_events(const SupportRaster& raster, std::vector<RawEvent>& raw, std::vector<int>& trim_begin,
                                    std::vector<std::pair<int, int>>& trims, std::vector<char>& has_contact) {
  const SlicerLayers& L = layers_;
  const int n = grid_.count(), count = L.count;
  const int reach = static_cast<int>(std::ceil(settings_.contact_distance / L.height - 1e-9));
  auto contact_layer = [&](int k) {
    const double top = L.bottom_z(k) - settings_.contact_distance + 1e-9;
    return top < L.first_height ? -1 : static_cast<int>(std::floor((top - L.first_height) / L.height));
  };
  std::vector<Range> solid, trim, contact, dense;
  size_t mark = 0;
  trim_begin.assign(static_cast<size_t>(n) + 1, 0);
  std::vector<int> solid_begin(static_cast<size_t>(n) + 1, 0);
  std::vector<Range> solids;
  for (int p = 0; p < n; ++p) {
    solid.clear(), trim.clear(), contact.clear(), dense.clear();
    trim_begin[p] = static_cast<int>(trims.size());
    for (int s = raster.span_begin[p]; s < raster.span_begin[p + 1]; ++s)
      append_merged(solid, L.first_slice_at_or_above(raster.spans[s].bottom),
                    std::min(count - 1, L.last_slice_at_or_below(raster.spans[s].top)));
    for (const Range& x : solid) {
      append_merged(trim, std::max(0, x.first - reach), std::min(count - 1, x.second + reach));
      add_range(raw, p, {x.second, x.second}, kTop);
    }
    solid_first_[p] = covers(solid, 0);
    trimmed_first_[p] = !trim.empty() && trim.front().first == 0;
    for (; mark < raster.overhangs.size() && raster.overhangs[mark].pixel == p; ++mark) {
      const PixelOverhang& o = raster.overhangs[mark];
      const int k_low = o.layer_low;
      if (k_low >= count) continue;
      if (k_low > 0 && inside_part(raster, L, p, k_low - 1)) continue;  // hidden
      const int high = contact_layer(std::min(count - 1, o.layer_high));
      if (high < 0) continue;
      const int low = std::max(0, contact_layer(k_low));
      append_merged(contact, low, high);
      if (o.dense) append_merged(dense, low, high);
    }
    for (const Range& x : trim) add_range(raw, p, x, kTrim);
    trims.insert(trims.end(), trim.begin(), trim.end());
    solid_begin[p] = static_cast<int>(solids.size());
    solids.insert(solids.end(), solid.begin(), solid.end());
    for (const Range& x : contact) {
      add_range(raw, p, x, kContact);
      for (int j = x.first; j <= x.second; ++j) has_contact[j] = 1;
    }
    for (const Range& x : dense) add_range(raw, p, x, kDense);
  }
  trim_begin[n] = static_cast<int>(trims.size());
  solid_begin[n] = static_cast<int>(solids.size());
  block_events({solid_begin, solids}, raw);
}

namespace {

// The layers at which the part's outline between pixel p and its neighbour q, though q is free,
// lies in q's half (past the midpoint between their centres), so p's half holds no sliver of
// support: where a run of q's solid layers starts above (ends below) one of p's, inside it, the
// outline runs from q's centre at q's first (last) solid slice to p's centre at p's, and passes
// the midpoint halfway between them. In layers, from the solid runs (the slicer sees slices only),
// so a closed part reads the same along rays and slice by slice. As block layers (j - 1 .. j for a
// slice at layer j), appended to `out` unsorted.
void outline_in_neighbour(const Range* p, const Range* p_end, const Range* q, const Range* q_end, std::vector<Range>& out) {
  auto add = [&](int k0, int k1) {
    if (k0 <= k1) out.push_back({std::max(0, k0 - 1), k1});
  };
  for (const Range* a = p; a != p_end; ++a)
    for (const Range* b = q; b != q_end; ++b) {
      if (b->first > a->first && b->first <= a->second) add((a->first + b->first + 1) / 2, b->first - 1);
      if (b->second < a->second && b->second >= a->first) add(b->second + 1, (a->second + b->second) / 2);
    }
}

// What blocks the projection at pixel p from its solid runs: the layers j filled at j or j + 1.
void blocked_layers(const Range* p, const Range* p_end, std::vector<Range>& out) {
  for (; p != p_end; ++p) append_merged(out, std::max(0, p->first - 1), p->second);
}

}  // namespace

// What stops a column: a pixel the part fills in both layers, and its four neighbours too, or
// those of them that are free only past the midpoint (outline_in_neighbour). The slicer's grid fill
// flows up to the part (it rasterises the part with any coverage), and a column whose cell keeps
// any sliver free goes on down: where the part recedes below, it fills the cell again. A sliver
// lies on p's side of the outline, so where the outline has left p's half, p blocks: a column
// coming down inside a bore lands on its floor instead of slipping down the outside of its wall.
void GridSupportSweep::block_events(const PixelRanges& solid, std::vector<RawEvent>& raw) const {
  std::vector<Range> eroded, scratch, covered, extra;
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      const int p = i + grid_.nx * j;
      if (solid.empty(p)) continue;
      if (i == 0 || j == 0 || i + 1 == grid_.nx || j + 1 == grid_.ny) continue;  // a neighbour off the raster is free
      eroded.clear();
      blocked_layers(solid.begin(p), solid.end(p), eroded);
      for (int q : {p - 1, p + 1, p - grid_.nx, p + grid_.nx}) {
        extra.clear();
        blocked_layers(solid.begin(q), solid.end(q), extra);
        outline_in_neighbour(solid.begin(p), solid.end(p), solid.begin(q), solid.end(q), extra);
        std::sort(extra.begin(), extra.end());
        covered.clear();
        for (const Range& x : extra) append_merged(covered, x.first, x.second);
        intersect(eroded.data(), eroded.data() + eroded.size(), covered.data(), covered.data() + covered.size(), scratch);
        eroded.swap(scratch);
        if (eroded.empty()) break;
      }
      for (const Range& x : eroded) add_range(raw, p, x, kBlock);
    }
  }
}

// The part's outline in every trimmed layer: an edge between a trimmed pixel and a free one is
// counted in the free pixel, where the xy gap and the sheath run along it.
void GridSupportSweep::outline_events(const std::vector<int>& trim_begin, const std::vector<std::pair<int, int>>& trims,
                                      std::vector<RawEvent>& raw) const {
  std::vector<Range> diff;
  for (int j = 0; j < grid_.ny; ++j) {
    for (int i = 0; i < grid_.nx; ++i) {
      const int p = i + grid_.nx * j;
      for (int q : {i + 1 < grid_.nx ? p + 1 : -1, j + 1 < grid_.ny ? p + grid_.nx : -1}) {
        if (q < 0 || (trim_begin[p] == trim_begin[p + 1] && trim_begin[q] == trim_begin[q + 1])) continue;
        const Range *a = trims.data() + trim_begin[p], *a_end = trims.data() + trim_begin[p + 1];
        const Range *b = trims.data() + trim_begin[q], *b_end = trims.data() + trim_begin[q + 1];
        subtract(a, a_end, b, b_end, diff);
        for (const Range& x : diff) add_range(raw, q, x, kOutline);
        subtract(b, b_end, a, a_end, diff);
        for (const Range& x : diff) add_range(raw, p, x, kOutline);
      }
    }
  }
}

GridSupportSweep::GridSupportSweep(const SupportRaster& raster, const SlicerLayers& layers, const GridSweepSettings& settings)
    : grid_(raster.grid), layers_(layers), settings_(settings) {
  if (layers.count <= 0 || settings.pixels_per_cell < 1) throw std::invalid_argument("support sweep: no layers or no cells");
  const int n = grid_.count(), count = layers.count;
  solid_first_.assign(static_cast<size_t>(n), 0);
  trimmed_first_.assign(static_cast<size_t>(n), 0);
  std::vector<RawEvent> raw;
  raw.reserve(static_cast<size_t>(24) * raster.spans.size() + 4 * raster.overhangs.size());
  std::vector<int> trim_begin;
  std::vector<Range> trims;
  std::vector<char> has_contact(static_cast<size_t>(count), 0);
  pixel_events(raster, raw, trim_begin, trims, has_contact);
  for (double t : support_layer_thickness(has_contact, layers, settings.max_support_layer_height))
    rates_.push_back(sweep_rates(settings, layers, t));
  outline_events(trim_begin, trims, raw);
  // Counting sort by layer, keeping each layer's events in the order they were made.
  event_begin_.assign(static_cast<size_t>(count) + 1, 0);
  for (const RawEvent& r : raw) ++event_begin_[r.layer + 1];
  for (int k = 0; k < count; ++k) {
    if (event_begin_[k + 1] > 0) top_layer_ = k;
    event_begin_[k + 1] += event_begin_[k];
  }
  events_.resize(raw.size());
  std::vector<int> fill(event_begin_.begin(), event_begin_.end() - 1);
  for (const RawEvent& r : raw) events_[fill[r.layer]++] = r.event;
}

}  // namespace slim
