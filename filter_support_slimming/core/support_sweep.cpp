#include "core/support_sweep.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace slim {
namespace {

using Range = std::pair<int, int>;  // [lo, hi] layers, inclusive
constexpr double kStaircase = M_PI / 4.0;  // mean true length of a pixel outline per pixel edge
constexpr int kNoDense = 1 << 29;

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

bool covers(const std::vector<Range>& ranges, int k) {
  for (const Range& r : ranges)
    if (r.first <= k && k <= r.second) return true;
  return false;
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

// Per pixel, in object layers: what the part fills, what trims a support layer there (the part
// within contact_distance above or below), what blocks the projection (filled at j or j + 1), the
// part's top layers, and the contacts (the support layer under each overhang).
void GridSupportSweep::pixel_events(const SupportRaster& raster, std::vector<RawEvent>& raw, std::vector<int>& trim_begin,
                                    std::vector<std::pair<int, int>>& trims, std::vector<char>& has_contact) {
  const SlicerLayers& L = layers_;
  const int n = grid_.count(), count = L.count;
  const int reach = static_cast<int>(std::ceil(settings_.contact_distance / L.height - 1e-9));
  auto contact_layer = [&](int k) {
    const double top = L.bottom_z(k) - settings_.contact_distance + 1e-9;
    return top < L.first_height ? -1 : static_cast<int>(std::floor((top - L.first_height) / L.height));
  };
  std::vector<Range> solid, trim, block, contact, dense;
  size_t mark = 0;
  trim_begin.assign(static_cast<size_t>(n) + 1, 0);
  for (int p = 0; p < n; ++p) {
    solid.clear(), trim.clear(), block.clear(), contact.clear(), dense.clear();
    trim_begin[p] = static_cast<int>(trims.size());
    for (int s = raster.span_begin[p]; s < raster.span_begin[p + 1]; ++s)
      append_merged(solid, L.first_slice_at_or_above(raster.spans[s].bottom),
                    std::min(count - 1, L.last_slice_at_or_below(raster.spans[s].top)));
    for (const Range& x : solid) {
      append_merged(trim, std::max(0, x.first - reach), std::min(count - 1, x.second + reach));
      append_merged(block, std::max(0, x.first - 1), x.second);
      add_range(raw, p, {x.second, x.second}, kTop);
    }
    solid_first_[p] = covers(solid, 0);
    trimmed_first_[p] = !trim.empty() && trim.front().first == 0;
    for (; mark < raster.overhangs.size() && raster.overhangs[mark].pixel == p; ++mark) {
      const PixelOverhang& o = raster.overhangs[mark];
      const int k_low = o.layer_low;
      if (k_low >= count || (k_low > 0 && covers(solid, k_low - 1))) continue;  // hidden inside the part
      const int high = contact_layer(std::min(count - 1, o.layer_high));
      if (high < 0) continue;
      const int low = std::max(0, contact_layer(k_low));
      append_merged(contact, low, high);
      if (o.dense) append_merged(dense, low, high);
    }
    for (const Range& x : trim) add_range(raw, p, x, kTrim);
    trims.insert(trims.end(), trim.begin(), trim.end());
    for (const Range& x : block) add_range(raw, p, x, kBlock);
    for (const Range& x : contact) {
      add_range(raw, p, x, kContact);
      for (int j = x.first; j <= x.second; ++j) has_contact[j] = 1;
    }
    for (const Range& x : dense) add_range(raw, p, x, kDense);
  }
  trim_begin[n] = static_cast<int>(trims.size());
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

namespace {

// One phase's cells: which cell every pixel lies in, and on which of its sides.
struct CellMap {
  int cx = 0, cy = 0;               // cells along x and y
  std::vector<int> cell;            // per pixel
  std::vector<std::uint8_t> sides;  // per pixel: bit s set when it lies along side s (-x, +x, -y, +y)
  CellMap(const PixelGrid& g, int per_cell, int ox, int oy) {
    cx = (g.nx + per_cell - 1) / per_cell + 1;
    cy = (g.ny + per_cell - 1) / per_cell + 1;
    cell.resize(static_cast<size_t>(g.count()));
    sides.resize(static_cast<size_t>(g.count()));
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const int a = i + per_cell - ox, b = j + per_cell - oy;  // shifted so cells start at the offset
        const int li = a % per_cell, lj = b % per_cell, p = i + g.nx * j;
        cell[p] = a / per_cell + cx * (b / per_cell);
        sides[p] = static_cast<std::uint8_t>((li == 0) | (li == per_cell - 1) << 1 | (lj == 0) << 2 | (lj == per_cell - 1) << 3);
      }
    }
  }
};

// The counters of one phase's cells at the current layer and the columns of the layer above.
struct PhaseState {
  int per_cell;
  struct Counters {
    int kind[GridSupportSweep::kKinds];
    int side_trimmed[4];  // trimmed pixels along each side (-x, +x, -y, +y)
  };
  std::vector<Counters> count;  // per cell
  std::vector<std::uint8_t> column_above, listed_contact;
  std::vector<int> dense_distance, seen, state_layer;
  std::vector<double> interface_weight, dense_depth;
  std::vector<int> above, now, contacts;
  PhaseState(int cells, int per_cell_) : per_cell(per_cell_) {
    count.assign(static_cast<size_t>(cells), Counters{});
    column_above.assign(static_cast<size_t>(cells), 0);
    listed_contact = column_above;
    dense_distance.assign(static_cast<size_t>(cells), kNoDense);
    seen.assign(static_cast<size_t>(cells), -1);
    state_layer = seen;
    interface_weight.assign(static_cast<size_t>(cells), 0.0);
    dense_depth = interface_weight;
  }
  void apply(const GridSupportSweep::Event& e, const CellMap& map) {
    const int c = map.cell[e.pixel];
    Counters& k = count[c];
    k.kind[e.kind] += e.delta;
    if (e.kind == GridSupportSweep::kTrim && map.sides[e.pixel])
      for (int s = 0; s < 4; ++s)
        if (map.sides[e.pixel] >> s & 1) k.side_trimmed[s] += e.delta;
    if (e.kind == GridSupportSweep::kContact && k.kind[e.kind] > 0 && !listed_contact[c]) {
      listed_contact[c] = 1;
      contacts.push_back(c);
    }
  }
};

// One layer's columns in figures: the base and interface areas, the base islands' outline (cell
// sides facing no base cell, and the part's outline inside base cells) where the sheath runs, and
// the base fill. PrusaSlicer's support lines run along x one grid cell apart, on the cell
// boundaries (its fill pattern is anchored where the grid is), so inside an island they lie on the
// boundaries between base cells, each ending fill_end short of the island's outline, and joined
// into a zigzag by links along the outline.
struct LayerFigures {
  double base_area = 0.0, interface_area = 0.0, outline = 0.0, fill_length = 0.0, contact_area = 0.0;
};

LayerFigures layer_figures(const PhaseState& st, const CellMap& map, const PixelGrid& grid, const GridSweepSettings& settings,
                           double fill_end, int j) {
  const int S = settings.pixels_per_cell, cells = map.cx * map.cy;
  const double p = grid.pixel, p2 = p * p, full = static_cast<double>(S) * S;
  auto base = [&](int c) { return c >= 0 && c < cells && st.state_layer[c] == j && st.interface_weight[c] < 0.5; };
  const int neighbour[4] = {-1, 1, -map.cx, map.cx};
  LayerFigures f;
  for (int c : st.now) {
    const PhaseState::Counters& k = st.count[c];
    const double area = std::max(0.0, (full - k.kind[GridSupportSweep::kTrim]) * p2 - settings.xy_gap * k.kind[GridSupportSweep::kOutline] * p * kStaircase);
    const double w = st.interface_weight[c];
    f.base_area += (1.0 - w) * area;
    f.interface_area += w * area;
    if (k.kind[GridSupportSweep::kContact] > 0) f.contact_area += area;
    if (!base(c)) continue;
    if (settings.sheath) {
      f.outline += k.kind[GridSupportSweep::kOutline] * p * kStaircase;
      for (int s = 0; s < 4; ++s)
        if (!base(c + neighbour[s])) f.outline += (S - k.side_trimmed[s]) * p;
    }
    // The line on the boundary with the cell above, and the link between it and the line below
    // where both end in this cell (the fill joins consecutive lines along the island's edge,
    // alternately at either end: half a link per such end).
    const int up = c + map.cx, down = c - map.cx;
    const bool line_up = base(up), line_down = base(down);
    if (line_up) f.fill_length += std::min(S - k.side_trimmed[3], S - st.count[up].side_trimmed[2]) * p;
    for (int side : {-1, 1}) {
      const bool end_up = line_up && !(base(c + side) && base(up + side));
      const bool end_down = line_down && !(base(c + side) && base(down + side));
      if (end_up) f.fill_length -= fill_end;
      if (end_up && end_down) f.fill_length += 0.5 * (S - k.side_trimmed[side < 0 ? 0 : 1]) * p;
    }
  }
  f.fill_length = std::max(0.0, f.fill_length);
  return f;
}

}  // namespace

GridSweepResult GridSupportSweep::run(int ox, int oy) const {
  const int S = settings_.pixels_per_cell;
  if (ox < 0 || oy < 0 || ox >= S || oy >= S) throw std::invalid_argument("support sweep: phase offset outside the cell");
  const CellMap map(grid_, S, ox, oy);
  const int cells = map.cx * map.cy;
  PhaseState st(cells, S);
  const double p2 = grid_.pixel * grid_.pixel, full = static_cast<double>(S) * S;
  GridSweepResult out;
  out.layer.assign(static_cast<size_t>(layers_.count), 0.0);
  for (int j = top_layer_; j >= 0; --j) {
    for (int e = event_begin_[j]; e < event_begin_[j + 1]; ++e) st.apply(events_[e], map);
    const SweepRates& rate = rates_[j];
    // Columns at j: contacts here, and columns above whose projection passes.
    st.now.clear();
    double landing = 0.0;
    auto consider = [&](int c) {
      if (st.seen[c] == j) return;
      st.seen[c] = j;
      const bool above = st.column_above[c] != 0;
      if (above) landing += st.count[c].kind[kTop] * p2;
      const bool contact = st.count[c].kind[kContact] > 0;
      if (!contact && !(above && st.count[c].kind[kBlock] < full)) return;
      st.now.push_back(c);
      if (st.count[c].kind[kDense] > 0) {
        st.dense_distance[c] = 0;
        st.dense_depth[c] = rate.interface_depth;
      } else {
        st.dense_distance[c] = above ? std::min(kNoDense, st.dense_distance[c] + 1) : kNoDense;
      }
      st.interface_weight[c] = std::clamp(st.dense_depth[c] - st.dense_distance[c], 0.0, 1.0);
      st.state_layer[c] = j;
    };
    for (int c : st.above) consider(c);
    size_t kept = 0;
    for (int c : st.contacts) {
      if (st.count[c].kind[kContact] <= 0) {
        st.listed_contact[c] = 0;
        continue;
      }
      st.contacts[kept++] = c;
      consider(c);
    }
    st.contacts.resize(kept);
    out.landing_area += landing;
    out.bottom_interface += landing * rate.bottom_interface_per_mm2;
    out.layer[j] += landing * rate.bottom_interface_per_mm2;
    const LayerFigures f = layer_figures(st, map, grid_, settings_, rate.fill_end, j);
    out.contact_area += f.contact_area;
    const double t = layers_.thickness(j);
    out.column_volume += t * (f.base_area + f.interface_area);
    if (j > 0) {
      const double fill = t * f.fill_length * rate.line_per_mm2;
      const double sheath = t * f.outline * rate.line_per_mm2, dense = t * f.interface_area * rate.interface_per_mm3;
      out.base_fill += fill;
      out.sheath += sheath;
      out.top_interface += dense;
      out.layer[j] += fill + sheath + dense;
    } else {
      out.first_layer = first_layer(st.now, map.cx, ox, oy);
      out.layer[0] += out.first_layer;
    }
    for (int c : st.above) st.column_above[c] = 0;
    for (int c : st.now) st.column_above[c] = 1;
    std::swap(st.above, st.now);
  }
  return out;
}

// The first layer: the columns' free pixels grown by first_layer_expansion in steps that go
// around the part's first slice (alternately to the 4 and the 8 neighbours: an octagon), filled
// at the first layer's density, with a sheath.
double GridSupportSweep::first_layer(const std::vector<int>& columns, int cells_x, int ox, int oy) const {
  const int nx = grid_.nx, ny = grid_.ny, S = settings_.pixels_per_cell;
  const int steps = static_cast<int>(std::lround(settings_.first_layer_expansion / grid_.pixel));
  int i0 = nx, i1 = -1, j0 = ny, j1 = -1;
  for (int c : columns) {  // the pixels of cell c: i + S - ox in [ci·S, ci·S + S)
    const int ci = c % cells_x, cj = c / cells_x;
    i0 = std::min(i0, std::max(0, ci * S - S + ox)), i1 = std::max(i1, std::min(nx, ci * S + ox) - 1);
    j0 = std::min(j0, std::max(0, cj * S - S + oy)), j1 = std::max(j1, std::min(ny, cj * S + oy) - 1);
  }
  if (i1 < i0 || j1 < j0) return 0.0;
  // A window over the columns grown by the steps and one more pixel; outside the raster is
  // walled off. Codes: 0 free, 1 support, 2 the part's first slice, 3 outside.
  const int wi0 = i0 - steps - 1, wj0 = j0 - steps - 1, w = i1 - i0 + 2 * steps + 3, h = j1 - j0 + 2 * steps + 3;
  std::vector<std::uint8_t> code(static_cast<size_t>(w) * h, 3);
  for (int b = 0; b < h; ++b)
    for (int a = 0; a < w; ++a) {
      const int i = wi0 + a, j = wj0 + b;
      if (i >= 0 && j >= 0 && i < nx && j < ny) code[a + w * b] = solid_first_[i + nx * j] ? 2 : 0;
    }
  for (int c : columns) {
    const int ci = c % cells_x, cj = c / cells_x;
    for (int j = std::max(0, cj * S - S + oy); j < std::min(ny, cj * S + oy); ++j)
      for (int i = std::max(0, ci * S - S + ox); i < std::min(nx, ci * S + ox); ++i)
        if (!trimmed_first_[i + nx * j]) code[(i - wi0) + w * (j - wj0)] = 1;
  }
  // Grown in steps to the 4 and then the 8 neighbours (an octagon), never into the part.
  std::vector<std::uint8_t> next;
  for (int step = 0; step < steps; ++step) {
    next = code;
    const bool diagonal = step % 2 == 1;
    for (int b = 1; b + 1 < h; ++b)
      for (int a = 1; a + 1 < w; ++a) {
        const int q = a + w * b;
        if (code[q] != 0) continue;
        bool reached = code[q - 1] == 1 || code[q + 1] == 1 || code[q - w] == 1 || code[q + w] == 1;
        if (diagonal) reached = reached || code[q - w - 1] == 1 || code[q - w + 1] == 1 || code[q + w - 1] == 1 || code[q + w + 1] == 1;
        if (reached) next[q] = 1;
      }
    code.swap(next);
  }
  double area = 0.0, outline = 0.0, along_part = 0.0;
  for (int b = 1; b + 1 < h; ++b)
    for (int a = 1; a + 1 < w; ++a) {
      const int q = a + w * b;
      if (code[q] != 1) continue;
      area += 1.0;
      for (int r : {q - 1, q + 1, q - w, q + w}) {
        if (code[r] == 1) continue;
        outline += 1.0;
        along_part += code[r] == 2;
      }
    }
  const double p = grid_.pixel;
  area = std::max(0.0, area * p * p - settings_.xy_gap * along_part * p * kStaircase);
  outline *= p * kStaircase;
  const SweepRates& rate = rates_[0];
  return rate.first_fill_per_mm2 * std::max(0.0, area - rate.first_inset * outline) + rate.first_sheath_per_mm * outline;
}

}  // namespace slim
